#include "core/sim/saturating_spring.h"

#include <cmath>

namespace handlab::sim {

SpringResponse saturating_spring(double k, double limit, const Eigen::Vector3d& d) {
  SpringResponse r;
  if (limit <= 0) {
    r.energy = 0.5 * k * d.squaredNorm();
    r.force = k * d;
    r.stiffness = k * Eigen::Matrix3d::Identity();
    return r;
  }
  const double l = limit / k, ratio2 = d.squaredNorm() / (l * l), s = std::sqrt(1 + ratio2);
  r.energy = k * l * l * ratio2 / (s + 1);  // k l^2 (s - 1), without its cancellation
  r.force = (k / s) * d;
  // Across d the force's gradient is k / s; along d, k / s^3.
  r.stiffness =
      (k / s) * Eigen::Matrix3d::Identity() - (k / (l * l * s * s * s)) * d * d.transpose();
  return r;
}

}  // namespace handlab::sim
