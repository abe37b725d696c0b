#include "core/sim/rigid_body.h"

#include <cmath>
#include <numbers>

namespace handlab::sim {

RigidInertia box_inertia(const Eigen::Vector3d& size, double density) {
  RigidInertia r;
  r.mass = density * size.prod();
  const Eigen::Vector3d s2 = size.cwiseAbs2();
  r.inertia = (r.mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()))
                  .asDiagonal();
  return r;
}

RigidInertia capsule_inertia(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
                             double density) {
  // Cylinder of length h plus two hemispheres, about the centre, axis along z first.
  const double h = (b - a).norm(), r2 = radius * radius, pi = std::numbers::pi;
  const double m_cyl = density * pi * r2 * h, m_sph = density * 4.0 / 3.0 * pi * r2 * radius;
  const double axial = m_cyl * r2 / 2.0 + m_sph * 2.0 * r2 / 5.0;
  // Each hemisphere: 2/5 m r^2 about its flat face's centre, less m (3r/8)^2 to its own centre
  // of mass (3r/8 from the face), plus m d^2 to the capsule's centre; the two weigh m_sph.
  const double c = 3.0 * radius / 8.0, d = h / 2.0 + c;
  const double transverse =
      m_cyl * (r2 / 4.0 + h * h / 12.0) + m_sph * (2.0 * r2 / 5.0 - c * c + d * d);
  RigidInertia out;
  out.mass = m_cyl + m_sph;
  out.centre = 0.5 * (a + b);
  const Eigen::Vector3d axis = h > 0 ? Eigen::Vector3d((b - a) / h) : Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d along = axis * axis.transpose();
  out.inertia = axial * along + transverse * (Eigen::Matrix3d::Identity() - along);
  return out;
}

RigidInertia combine(const std::vector<RigidInertia>& parts) {
  RigidInertia out;
  for (const RigidInertia& p : parts) {
    out.mass += p.mass;
    out.centre += p.mass * p.centre;
  }
  if (out.mass > 0) out.centre /= out.mass;
  for (const RigidInertia& p : parts) {
    const Eigen::Vector3d d = p.centre - out.centre;
    out.inertia +=
        p.inertia + p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

Eigen::Quaterniond rotation_from_vector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12)
    return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

Eigen::Vector3d rotation_vector(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond p = q;
  if (p.w() < 0) p.coeffs() = -p.coeffs();  // the shorter way round
  const double s = p.vec().norm();
  if (s < 1e-12) return 2.0 * p.vec();
  return 2.0 * std::atan2(s, p.w()) * p.vec() / s;
}

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace handlab::sim
