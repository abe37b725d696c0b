#include "studies/participant/pinch_ik.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace handlab::studies {
namespace {

// The parameters it moves: the root's translation (3) and every joint angle; the rotation's
// three columns of the skeleton's Jacobian are left out.
void moved_columns(const Eigen::Matrix<double, 3, Eigen::Dynamic>& full, Eigen::MatrixXd& j) {
  j.resize(3, full.cols() - 3);
  j.leftCols<3>() = full.leftCols<3>();
  j.rightCols(full.cols() - 6) = full.rightCols(full.cols() - 6);
}

}  // namespace

PinchIkResult solve_pinch_ik(const hand::Skeleton& skeleton, hand::HandPose& pose,
                             const std::vector<PointGoal>& goals, const PinchIkOptions& options) {
  const int dofs = int(skeleton.dofs.size());
  const int n = 3 + dofs;
  const Eigen::Vector3d root_start = pose.root_position;
  PinchIkResult result;
  // Storage kept across the iterations.
  hand::BoneFrames frames;
  Eigen::Matrix<double, 3, Eigen::Dynamic> full;
  Eigen::MatrixXd j, normal;
  Eigen::VectorXd gradient, step, scaled;
  Eigen::LDLT<Eigen::MatrixXd> ldlt(n);
  std::vector<bool> held(static_cast<std::size_t>(n));
  for (int it = 0; it < options.iterations; ++it) {
    hand::forward_kinematics(skeleton, pose, frames);
    normal.setZero(n, n);
    gradient.setZero(n);
    for (const PointGoal& g : goals) {
      const Eigen::Vector3d p = hand::bone_point(frames, g.bone, g.local);
      hand::point_jacobian(skeleton, frames, pose, g.bone, p, full);
      moved_columns(full, j);
      normal.noalias() += g.weight * j.transpose() * j;
      gradient.noalias() += g.weight * j.transpose() * (p - g.target);
    }
    normal.topLeftCorner<3, 3>().diagonal().array() += options.root_weight;
    gradient.head<3>() += options.root_weight * (pose.root_position - root_start);
    // Joints at a limit that the step would push past are held there (a projected step).
    std::fill(held.begin(), held.end(), false);
    for (int k = 0; k < dofs; ++k) {
      const double a = pose.angles(k);
      const hand::Dof& d = skeleton.dofs[std::size_t(k)];
      held[std::size_t(3 + k)] = (a <= d.lower + 1e-12 && gradient(3 + k) > 0) ||
                                 (a >= d.upper - 1e-12 && gradient(3 + k) < 0);
    }
    for (int k = 0; k < n; ++k) {
      normal(k, k) += options.damping;
      if (!held[std::size_t(k)]) continue;
      normal.row(k).setZero();
      normal.col(k).setZero();
      normal(k, k) = 1.0;
      gradient(k) = 0.0;
    }
    ldlt.compute(normal);
    step = ldlt.solve(gradient);
    step = -step;
    scaled = step;
    scaled.head<3>() /= options.translation_unit;
    const double longest = scaled.cwiseAbs().maxCoeff();
    if (longest > options.max_step) step *= options.max_step / longest;
    pose.root_position += step.head<3>();
    for (int k = 0; k < dofs; ++k) {
      const hand::Dof& d = skeleton.dofs[std::size_t(k)];
      pose.angles(k) = std::clamp(pose.angles(k) + step(3 + k), d.lower, d.upper);
    }
    result.iterations = it + 1;
    if (step.cwiseAbs().maxCoeff() < options.step_tolerance) break;
  }
  hand::forward_kinematics(skeleton, pose, frames);
  double weighted = 0.0, weights = 0.0;
  for (const PointGoal& g : goals) {
    weighted += g.weight * (hand::bone_point(frames, g.bone, g.local) - g.target).squaredNorm();
    weights += g.weight;
  }
  result.residual = weights > 0 ? std::sqrt(weighted / weights) : 0.0;
  return result;
}

}  // namespace handlab::studies
