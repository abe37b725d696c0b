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

}  // namespace handlab::sim
