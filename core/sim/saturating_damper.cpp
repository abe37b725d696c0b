#include "core/sim/saturating_damper.h"

#include <cmath>

namespace handlab::sim {

SpringResponse saturating_damper(double c, double v0, double h, const Eigen::Vector3d& d) {
  const Eigen::Vector3d v = d / h;
  SpringResponse r;
  if (v0 <= 0) {
    r.energy = 0.5 * c * h * v.squaredNorm();
    r.force = c * v;
    r.stiffness = (c / h) * Eigen::Matrix3d::Identity();
    return r;
  }
  const double speed = v.norm(), u = speed / v0;
  r.energy = h * c * v0 * v0 * (u - std::log1p(u));
  r.force = c * v / (1 + u);
  // Across v the force's gradient in v is c / (1 + u); along v, c / (1 + u)^2.
  r.stiffness = (c / (1 + u) / h) * Eigen::Matrix3d::Identity();
  if (speed > 0) {
    const Eigen::Vector3d n = v / speed;
    r.stiffness += (c / h) * (1 / ((1 + u) * (1 + u)) - 1 / (1 + u)) * n * n.transpose();
  }
  return r;
}

}  // namespace handlab::sim
