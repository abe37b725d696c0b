// The built-in open-loop participant motion: a tracked skeleton of the participant's hand
// length holds an open palm (for calibration), reaches over zone A, pinches the cube
// between thumb and index, lifts it 10 cm, carries it over zone B, puts it down, opens and
// withdraws. It is planned in the scene with the session's calibration scale (as a person
// sees the virtual hand), then played at a fixed rate; it never looks at the cube.
#pragma once

#include <vector>

#include "core/hand/skeleton.h"
#include "core/retarget/retargeter.h"
#include "core/task/scene_layout.h"
#include "core/tracking/frame_source.h"

namespace handlab::studies {

class SessionControl;

struct ScriptedMotionSettings {
  double hand_length = 0.18;            // the participant's (m)
  double scale = 0.214 / 0.18;          // the session's calibration (simulated / tracked)
  double simulated_tip_radius = 0.004;  // m: fingertip sphere of the simulated hand
  task::SceneLayout layout;             // zones and the cube of this condition
  double rate_hz = 120.0;
  double tempo = 1.0;  // > 1 slower: every phase of the motion takes this much longer
};

// A second of the open palm held over zone A: what calibration measures.
std::vector<tracking::TrackedFrame> scripted_open_palm(const ScriptedMotionSettings& settings);

// How the scripted and the simulated participant calibrate: a second of the open palm of a
// hand of the participant's length over zone A, measured for `first_hand` (the first
// condition's simulated hand); the outcome reported to `control` (may be null).
retarget::Calibration scripted_calibration(const task::SceneLayout& scene, double hand_length,
                                           const hand::Skeleton& first_hand,
                                           SessionControl* control);

class ScriptedTracker : public tracking::FrameSource {
 public:
  explicit ScriptedTracker(const ScriptedMotionSettings& settings);
  std::optional<tracking::TrackedFrame> next() override;
  double duration() const;  // s

 private:
  struct Key {
    double time;
    Eigen::Vector3d root_position;
    Eigen::VectorXd angles;
  };
  ScriptedMotionSettings settings_;
  hand::Skeleton skeleton_;
  Eigen::Matrix3d root_rotation_;
  std::vector<Key> keys_;
  long frame_ = 0;
};

}  // namespace handlab::studies
