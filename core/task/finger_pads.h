// Where a finger's pad is: on the palmar side of its distal bone's middle, as far out as the
// flesh reaches there at rest. The scripted pinch aims the pads at the cube's faces
// (pinch_script.h), and a logged grasp's closing is read at them (studies/analysis).
#pragma once

#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"

namespace handlab::sim {

// The pad of `bone` (a distal bone) in that bone's frame: 0.55 of its length along it, at the
// depth of the palmar flesh there. Throws std::invalid_argument when no flesh lies there.
Eigen::Vector3d finger_pad(const hand::Skeleton& skeleton, const HandSimModel& model, int bone);

// The pads of a pinch: each a point in its distal bone's frame.
struct PinchPads {
  int thumb_bone = -1, index_bone = -1;
  Eigen::Vector3d thumb_pad = Eigen::Vector3d::Zero(), index_pad = Eigen::Vector3d::Zero();
};

// The thumb's and index's pads (thumb3, index3); throws std::invalid_argument for a hand
// without those bones.
PinchPads pinch_pads(const hand::Skeleton& skeleton, const HandSimModel& model);

// Where the pads are with the bones at `frames`.
struct PadPoints {
  Eigen::Vector3d thumb, index;
};
PadPoints pad_points(const hand::BoneFrames& frames, const PinchPads& pads);

}  // namespace handlab::sim
