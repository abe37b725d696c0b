#include "core/sim/rotation_extraction.h"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace handlab::sim {
namespace {

// Newton's method on the polar condition "R'F is symmetric": with G = R'F = S + W (symmetric
// and skew parts), a body-frame turn d with (tr(S) I - S) d = axial(G - G') cancels W to first
// order. Converges quadratically while S is positive definite (F not inverted relative to R).
bool newton_polar(const Eigen::Matrix3d& f, Eigen::Quaterniond& q) {
  for (int i = 0; i < 8; ++i) {
    const Eigen::Matrix3d g = q.toRotationMatrix().transpose() * f;
    const Eigen::Vector3d skew(g(2, 1) - g(1, 2), g(0, 2) - g(2, 0), g(1, 0) - g(0, 1));
    const Eigen::Matrix3d s = 0.5 * (g + g.transpose());
    const Eigen::Matrix3d m = s.trace() * Eigen::Matrix3d::Identity() - s;
    // m positive definite (Sylvester), by a margin relative to F's size.
    const double scale = f.cwiseAbs().maxCoeff() + 1e-300;
    if (!(m(0, 0) > 1e-3 * scale) ||
        !(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) > 1e-6 * scale * scale) ||
        !(m.determinant() > 1e-9 * scale * scale * scale))
      return false;
    const Eigen::Vector3d d = m.inverse() * skew;
    const double angle = d.norm();
    if (!(angle < 0.5)) return false;
    // The turn by d: the half-angle quaternion, by its series below 0.05 rad (to the fourth
    // order: what it leaves out is below 1e-12).
    if (angle > 0.05) {
      const double half = 0.5 * angle, sine = std::sin(half) / angle;
      q = q * Eigen::Quaterniond(std::cos(half), sine * d.x(), sine * d.y(), sine * d.z());
    } else {
      const double h2 = 0.25 * angle * angle;  // (angle / 2)^2
      const double cosine = 1.0 - h2 / 2 + h2 * h2 / 24;
      const double sine = 0.5 * (1.0 - h2 / 6 + h2 * h2 / 120);  // sin(angle / 2) / angle
      q = q * Eigen::Quaterniond(cosine, sine * d.x(), sine * d.y(), sine * d.z());
    }
    q.normalize();
    // Quadratic convergence: after a turn of 1e-5 rad what is left is about 1e-10 rad.
    if (angle < 1e-5) return true;
  }
  return false;
}

}  // namespace

void extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations) {
  if (newton_polar(f, q)) return;
  for (int i = 0; i < max_iterations; ++i) {
    const Eigen::Matrix3d r = q.toRotationMatrix();
    // The torque that turns R's columns towards F's, over their alignment.
    const Eigen::Vector3d omega =
        (r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2))) /
        (std::abs(r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2))) + 1e-9);
    const double w = omega.norm();
    if (w < 1e-12) return;
    q = Eigen::Quaterniond(Eigen::AngleAxisd(w, omega / w)) * q;
    q.normalize();
    // Once near, Newton finishes quadratically.
    if (w < 0.05 && newton_polar(f, q)) return;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) = -u.col(2);
  q = Eigen::Quaterniond(u * svd.matrixV().transpose());
  q.normalize();
}

}  // namespace handlab::sim
