#include "core/sim/corotated_tet.h"

#include <stdexcept>

namespace handlab::sim {

TetElement make_tet_element(const std::array<Eigen::Vector3d, 4>& rest,
                            const std::array<int, 4>& nodes, const Material& material) {
  Eigen::Matrix3d dm;
  for (int k = 0; k < 3; ++k) dm.col(k) = rest[std::size_t(k + 1)] - rest[0];
  const double det = dm.determinant();
  if (!(det > 0.0)) throw std::invalid_argument("a degenerate or inverted rest tetrahedron");
  TetElement tet;
  tet.nodes = nodes;
  tet.volume = det / 6.0;
  // grad N_1..3 are the rows of Dm^-1; grad N_0 = -(their sum).
  const Eigen::Matrix3d dm_inv = dm.inverse();
  for (int a = 1; a < 4; ++a) tet.gradients.col(a) = dm_inv.row(a - 1).transpose();
  tet.gradients.col(0) = -(tet.gradients.col(1) + tet.gradients.col(2) + tet.gradients.col(3));
  // K_ab = V [mu ((gN_a . gN_b) I + gN_b gN_a') + lambda gN_a gN_b'].
  const double mu = material.mu(), lambda = material.lambda();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const Eigen::Vector3d ga = tet.gradients.col(a), gb = tet.gradients.col(b);
      tet.stiffness.block<3, 3>(3 * a, 3 * b) =
          tet.volume * (mu * (ga.dot(gb) * Eigen::Matrix3d::Identity() + gb * ga.transpose()) +
                        lambda * ga * gb.transpose());
    }
  return tet;
}

Eigen::Matrix3d deformation_gradient(const TetElement& tet,
                                     const std::array<Eigen::Vector3d, 4>& x) {
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 4; ++a) f += x[std::size_t(a)] * tet.gradients.col(a).transpose();
  return f;
}

Eigen::Matrix3d corotated_strain(const TetElement& tet, const std::array<Eigen::Vector3d, 4>& x,
                                 const Eigen::Matrix3d& rotation) {
  const Eigen::Matrix3d g = rotation.transpose() * deformation_gradient(tet, x);
  return 0.5 * (g + g.transpose()) - Eigen::Matrix3d::Identity();
}

void evaluate_corotated(const TetElement& tet, const std::array<Eigen::Vector3d, 4>& rest,
                        const std::array<Eigen::Vector3d, 4>& x, const Eigen::Matrix3d& rotation,
                        ElementEvaluation& out, bool with_hessian) {
  // u = R'x - X, less a common translation (K annihilates it): relative to node 0, so that a
  // body far from the origin loses no digits.
  Vector12d u;
  u.head<3>().setZero();
  for (int a = 1; a < 4; ++a)
    u.segment<3>(3 * a) =
        rotation.transpose() * (x[std::size_t(a)] - x[0]) - (rest[std::size_t(a)] - rest[0]);
  const Vector12d local = tet.stiffness * u;
  out.energy = 0.5 * u.dot(local);
  for (int a = 0; a < 4; ++a) out.gradient.segment<3>(3 * a) = rotation * local.segment<3>(3 * a);
  if (!with_hessian) return;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      out.hessian.block<3, 3>(3 * a, 3 * b) =
          rotation * tet.stiffness.block<3, 3>(3 * a, 3 * b) * rotation.transpose();
}

}  // namespace handlab::sim
