#include "core/task/pose_least_squares.h"

#include <algorithm>

#include <Eigen/Cholesky>

#include "core/sim/rigid_body.h"

namespace handlab::sim {

hand::HandPose moved_pose(const hand::Skeleton& skeleton, const hand::HandPose& pose,
                          const std::vector<int>& dofs, const Eigen::VectorXd& x, bool free_wrist) {
  hand::HandPose out = pose;
  const Eigen::Index first = free_wrist ? 6 : 0;
  if (free_wrist) {
    out.root_rotation = rotation_from_vector(x.head<3>()).toRotationMatrix() * pose.root_rotation;
    out.root_position += x.segment<3>(3);
  }
  for (std::size_t j = 0; j < dofs.size(); ++j) {
    const hand::Dof& dof = skeleton.dofs[std::size_t(dofs[j])];
    const Eigen::Index k = dofs[j];
    out.angles(k) = std::clamp(pose.angles(k) + x(first + Eigen::Index(j)), dof.lower, dof.upper);
  }
  return out;
}

hand::HandPose solve_pose_least_squares(hand::HandPose pose, Eigen::Index unknowns,
                                        const PoseResiduals& residuals, const PoseStep& moved,
                                        const PoseLeastSquares& options) {
  Eigen::VectorXd r = residuals(pose);
  double damping = 1e-3;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    Eigen::MatrixXd jacobian(r.size(), unknowns);
    for (Eigen::Index j = 0; j < unknowns; ++j) {
      const Eigen::VectorXd step = Eigen::VectorXd::Unit(unknowns, j) * options.difference;
      jacobian.col(j) = (residuals(moved(pose, step)) - r) / options.difference;
    }
    const Eigen::MatrixXd normal = jacobian.transpose() * jacobian;
    const Eigen::VectorXd gradient = jacobian.transpose() * r;
    bool lower = false;
    for (int attempt = 0; attempt < options.attempts && !lower; ++attempt) {
      Eigen::MatrixXd damped = normal;
      damped.diagonal() += damping * (normal.diagonal().array() + options.diagonal_floor).matrix();
      const hand::HandPose trial = moved(pose, -damped.ldlt().solve(gradient));
      const Eigen::VectorXd trial_r = residuals(trial);
      lower = trial_r.squaredNorm() < r.squaredNorm() * (1 - options.relative_decrease);
      if (lower) {
        pose = trial;
        r = trial_r;
        damping *= 0.3;
      } else {
        damping *= 10;
      }
    }
    if (!lower) break;
  }
  return pose;
}

}  // namespace handlab::sim
