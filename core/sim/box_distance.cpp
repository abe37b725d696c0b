#include "core/sim/box_distance.h"

#include <cmath>

namespace handlab::sim {

BoxProximity box_proximity(const Eigen::Vector3d& half, const Eigen::Vector3d& q) {
  BoxProximity out;
  const Eigen::Vector3d clamped = q.cwiseMax(-half).cwiseMin(half);
  const Eigen::Vector3d outside = q - clamped;
  const double gap = outside.norm();
  if (gap > 0) {
    out.distance = gap;
    out.closest = clamped;
    out.normal = outside / gap;
    return out;
  }
  // Inside: the nearest face is the one with the least depth.
  int axis = 0;
  double depth = half(0) - std::abs(q(0));
  for (int k = 1; k < 3; ++k)
    if (half(k) - std::abs(q(k)) < depth) {
      depth = half(k) - std::abs(q(k));
      axis = k;
    }
  const double side = q(axis) >= 0 ? 1.0 : -1.0;
  out.distance = -depth;
  out.closest = q;
  out.closest(axis) = side * half(axis);
  out.normal = side * Eigen::Vector3d::Unit(axis);
  return out;
}

bool beyond_box(const Eigen::Vector3d& half, const Eigen::Vector3d& q, double reach) {
  // The norm is at least the largest gap (the rounding of its squares' sum is monotone); the
  // margin is for any contraction of that sum into fused operations.
  return reach > 0 && (q.cwiseAbs() - half).maxCoeff() > reach * (1 + 1e-9);
}

int box_face(const Eigen::Vector3d& half, const Eigen::Vector3d& q) {
  int face = 0;
  double farthest = -INFINITY;
  for (int axis = 0; axis < 3; ++axis)
    for (int positive = 1; positive >= 0; --positive) {
      const double outside = (positive ? q(axis) : -q(axis)) - half(axis);
      if (outside > farthest) {
        farthest = outside;
        face = 2 * axis + positive;
      }
    }
  return face;
}

BoxProximity box_proximity_through(const Eigen::Vector3d& half, const Eigen::Vector3d& q,
                                   int face) {
  if ((q.array().abs() > half.array()).any()) return box_proximity(half, q);
  const int axis = face / 2;
  const double side = face % 2 ? 1.0 : -1.0;
  BoxProximity out;
  out.distance = side * q(axis) - half(axis);
  out.closest = q;
  out.closest(axis) = side * half(axis);
  out.normal = side * Eigen::Vector3d::Unit(axis);
  return out;
}

}  // namespace handlab::sim
