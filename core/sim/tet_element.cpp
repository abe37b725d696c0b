#include "core/sim/tet_element.h"

#include <stdexcept>

#include <Eigen/LU>

namespace handlab::sim {

TetElement make_tet_element(const std::array<Eigen::Vector3d, 4>& rest,
                            const std::array<int, 4>& nodes) {
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

}  // namespace handlab::sim
