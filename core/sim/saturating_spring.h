// A spring whose force saturates, as a virtual coupling's does (Colgate, Stanley & Brown
// 1995): the pseudo-Huber energy k l^2 (sqrt(1 + |d|^2 / l^2) - 1), l = limit / k. Like
// k |d|^2 / 2 where |d| << l, its force k d / sqrt(1 + |d|^2 / l^2) approaches `limit` and
// never passes it; smooth and convex, so Newton's matrix stays positive definite.
#pragma once

#include <Eigen/Core>

namespace handlab::sim {

struct SpringResponse {
  double energy = 0.0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();      // the energy's gradient
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  // its Hessian
};

// The spring of stiffness k (N/m or N m/rad) stretched by d, its force bounded by `limit`
// (N or N m; 0: a linear spring).
SpringResponse saturating_spring(double k, double limit, const Eigen::Vector3d& d);

}  // namespace handlab::sim
