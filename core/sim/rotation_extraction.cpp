#include "core/sim/rotation_extraction.h"

#include <algorithm>
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

void rotation_matrices(const Eigen::Array4d& w, const Eigen::Array4d& x, const Eigen::Array4d& y,
                       const Eigen::Array4d& z, Eigen::Array4d (&r)[9]) {
  r[0] = 1 - 2 * (y.square() + z.square());
  r[1] = 2 * (x * y - z * w);
  r[2] = 2 * (x * z + y * w);
  r[3] = 2 * (x * y + z * w);
  r[4] = 1 - 2 * (x.square() + z.square());
  r[5] = 2 * (y * z - x * w);
  r[6] = 2 * (x * z - y * w);
  r[7] = 2 * (y * z + x * w);
  r[8] = 1 - 2 * (x.square() + y.square());
}

int extract_rotations(const Eigen::Array4d (&f)[9], Eigen::Quaterniond* const (&q)[4], int count) {
  using Lane4 = Eigen::Array4d;
  Lane4 w, x, y, z, scale = Lane4::Constant(1e-300);
  for (int l = 0; l < 4; ++l) {
    const Eigen::Quaterniond& start = *q[std::min(l, count - 1)];
    w[l] = start.w();
    x[l] = start.x();
    y[l] = start.y();
    z[l] = start.z();
  }
  for (const Lane4& v : f) scale = scale.max(v.abs());
  // newton_polar's iteration in each lane (its series turn only: a larger turn unsettles).
  Eigen::Array<bool, 4, 1> settled = Eigen::Array<bool, 4, 1>::Constant(true);
  for (int iteration = 0; iteration < 2; ++iteration) {
    Lane4 r[9];
    rotation_matrices(w, x, y, z, r);
    auto g = [&](int i, int j) {  // (R'F)_ij
      return Lane4(r[i] * f[j] + r[3 + i] * f[3 + j] + r[6 + i] * f[6 + j]);
    };
    const Lane4 g01 = g(0, 1), g10 = g(1, 0), g02 = g(0, 2), g20 = g(2, 0), g12 = g(1, 2),
                g21 = g(2, 1), g00 = g(0, 0), g11 = g(1, 1), g22 = g(2, 2);
    const Lane4 skew0 = g21 - g12, skew1 = g02 - g20, skew2 = g10 - g01;
    // M = tr(S) I - S (S = sym(R'F)), symmetric: its adjugate and determinant.
    const Lane4 m00 = g11 + g22, m11 = g00 + g22, m22 = g00 + g11;
    const Lane4 m01 = -0.5 * (g01 + g10), m02 = -0.5 * (g02 + g20), m12 = -0.5 * (g12 + g21);
    const Lane4 a00 = m11 * m22 - m12 * m12, a01 = m02 * m12 - m01 * m22,
                a02 = m01 * m12 - m02 * m11, a11 = m00 * m22 - m02 * m02,
                a12 = m01 * m02 - m00 * m12, a22 = m00 * m11 - m01 * m01;
    const Lane4 det = m00 * a00 + m01 * a01 + m02 * a02;
    const auto definite = (m00 > 1e-3 * scale) && (m00 * m11 - m01 * m01 > 1e-6 * scale.square()) &&
                          (det > 1e-9 * scale.cube());
    const Lane4 inverse = definite.select(1.0 / det, 0.0);
    const Lane4 d0 = inverse * (a00 * skew0 + a01 * skew1 + a02 * skew2);
    const Lane4 d1 = inverse * (a01 * skew0 + a11 * skew1 + a12 * skew2);
    const Lane4 d2 = inverse * (a02 * skew0 + a12 * skew1 + a22 * skew2);
    const Lane4 squared = d0.square() + d1.square() + d2.square(), h2 = 0.25 * squared;
    const Lane4 tw = 1.0 - h2 / 2 + h2.square() / 24;
    const Lane4 sine = 0.5 * (1.0 - h2 / 6 + h2.square() / 120);
    const Lane4 tx = sine * d0, ty = sine * d1, tz = sine * d2;
    // q times the turn, normalised.
    const Lane4 nw = w * tw - x * tx - y * ty - z * tz;
    const Lane4 nx = w * tx + x * tw + y * tz - z * ty;
    const Lane4 ny = w * ty - x * tz + y * tw + z * tx;
    const Lane4 nz = w * tz + x * ty - y * tx + z * tw;
    const Lane4 norm = (nw.square() + nx.square() + ny.square() + nz.square()).rsqrt();
    w = nw * norm;
    x = nx * norm;
    y = ny * norm;
    z = nz * norm;
    // The series holds below 0.05 rad; the second turn must show convergence (1e-5 rad).
    const double limit = iteration == 0 ? 0.05 : 1e-5;
    settled = settled && definite && (squared < limit * limit);
  }
  int settled_lanes = 0;
  for (int l = 0; l < count; ++l) {
    if (settled[l]) {
      *q[l] = Eigen::Quaterniond(w[l], x[l], y[l], z[l]);
      ++settled_lanes;
      continue;
    }
    Eigen::Matrix3d m;
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = f[i][l];
    extract_rotation(m, *q[l]);
  }
  return settled_lanes;
}

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
