#include "tests/core/sim/reference/corotated_element.h"

namespace handlab::sim {

Matrix12d corotated_stiffness(const TetElement& tet, const Material& material) {
  Matrix12d stiffness;
  // K_ab = V [mu ((gN_a . gN_b) I + gN_b gN_a') + lambda gN_a gN_b'].
  const double mu = material.mu(), lambda = material.lambda();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const Eigen::Vector3d ga = tet.gradients.col(a), gb = tet.gradients.col(b);
      stiffness.block<3, 3>(3 * a, 3 * b) =
          tet.volume * (mu * (ga.dot(gb) * Eigen::Matrix3d::Identity() + gb * ga.transpose()) +
                        lambda * ga * gb.transpose());
    }
  return stiffness;
}

void evaluate_corotated(const Matrix12d& stiffness, const std::array<Eigen::Vector3d, 4>& rest,
                        const std::array<Eigen::Vector3d, 4>& x, const Eigen::Matrix3d& rotation,
                        ElementEvaluation& out, bool with_hessian) {
  // u = R'x - X, less a common translation (K annihilates it): relative to node 0, so that a
  // body far from the origin loses no digits.
  Vector12d u;
  u.head<3>().setZero();
  for (int a = 1; a < 4; ++a)
    u.segment<3>(3 * a) =
        rotation.transpose() * (x[std::size_t(a)] - x[0]) - (rest[std::size_t(a)] - rest[0]);
  const Vector12d local = stiffness * u;
  out.energy = 0.5 * u.dot(local);
  for (int a = 0; a < 4; ++a) out.gradient.segment<3>(3 * a) = rotation * local.segment<3>(3 * a);
  if (!with_hessian) return;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      out.hessian.block<3, 3>(3 * a, 3 * b) =
          rotation * stiffness.block<3, 3>(3 * a, 3 * b) * rotation.transpose();
}

}  // namespace handlab::sim
