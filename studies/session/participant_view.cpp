#include "studies/session/participant_view.h"

#include "core/hand/simulated_hand.h"
#include "core/render/frame_drawing.h"
#include "core/render/scene_drawing.h"

namespace handlab::studies {

void ParticipantView::start_trial(const TrialSetup& setup) {
  layout_ = trial_layout(setup);
  const hand::HandShape& shape = setup.condition.simulated_hand;
  if (bones_.capsules.empty() || shape_.length != shape.length ||
      shape_.hand_breadth() != shape.hand_breadth()) {
    bones_ = render::make_bone_meshes(hand::build_simulated_hand(shape));
    shape_ = shape;
  }
}

render::DrawList ParticipantView::draw(const TrialStep& step) const {
  if (!step.frame) return render::draw_task_scene(layout_, task::cube_start_pose(layout_));
  if (step.flesh && step.flesh_nodes)
    return render::draw_soft_hand_frame(layout_, step.flesh->render, step.flesh->tets,
                                        *step.flesh_nodes, *step.frame);
  return render::draw_stored_frame(layout_, bones_, *step.frame);
}

}  // namespace handlab::studies
