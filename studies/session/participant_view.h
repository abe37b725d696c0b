// What the participant sees after a session's step, as a drawing: the trial's scene with the
// cube where the step left it and the simulated hand, its skin where the soft hand's flesh is
// or its bones on the grasp proxy. A front end that draws it elsewhere than the app's window
// (the headset) builds it here.
#pragma once

#include "core/hand/hand_shape.h"
#include "core/render/draw_list.h"
#include "core/render/hand_drawing.h"
#include "core/task/scene_layout.h"
#include "studies/session/session_control.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

class ParticipantView {
 public:
  // The trial's scene and the condition's hand (its bones' meshes made again only when the
  // hand changes).
  void start_trial(const TrialSetup& setup);
  render::DrawList draw(const TrialStep& step) const;
  const task::SceneLayout& layout() const { return layout_; }

 private:
  task::SceneLayout layout_;
  hand::HandShape shape_;
  render::BoneMeshes bones_;
};

}  // namespace handlab::studies
