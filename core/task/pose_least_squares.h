// Levenberg-Marquardt over a hand pose: the residuals of a pose, the pose moved by a step of
// its unknowns, the Jacobian by forward differences. The pinch's rule (pinch_clearance.h) and
// the functional posture (pinch_posture.h) place the hand with it.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"

namespace handlab::sim {

struct PoseLeastSquares {
  int iterations = 300;
  double difference = 1e-6;  // the forward differences' step (m, rad)
  // Each iteration tries up to `attempts` dampings, from the last one that lowered the sum of
  // squares times 0.3, each a failure's times 10, on the normal matrix's diagonal plus
  // `diagonal_floor`; a step is taken where it lowers the sum by more than `relative_decrease`
  // of itself. The iterations end where no attempt does.
  int attempts = 10;
  double diagonal_floor = 1e-9;
  double relative_decrease = 0.0;
};

using PoseResiduals = std::function<Eigen::VectorXd(const hand::HandPose&)>;
using PoseStep = std::function<hand::HandPose(const hand::HandPose&, const Eigen::VectorXd&)>;

// `pose` moved by x: with `free_wrist` the wrist turned by x[0..3] (a rotation vector, world,
// about the wrist) and moved by x[3..6]; then joint dofs[j] by the j-th of the rest of x,
// within its limits.
hand::HandPose moved_pose(const hand::Skeleton& skeleton, const hand::HandPose& pose,
                          const std::vector<int>& dofs, const Eigen::VectorXd& x, bool free_wrist);

// From `pose`, over `unknowns` unknowns.
hand::HandPose solve_pose_least_squares(hand::HandPose pose, Eigen::Index unknowns,
                                        const PoseResiduals& residuals, const PoseStep& moved,
                                        const PoseLeastSquares& options);

}  // namespace handlab::sim
