// A linear tetrahedron of the flesh as the simulator reads it: its nodes, rest volume and the
// rest gradients of its shape functions (flesh_energy.h evaluates its co-rotational energy),
// and the elastic material.
#pragma once

#include <array>

#include <Eigen/Core>

namespace handlab::sim {

struct Material {
  double youngs_modulus = 0.0;  // Pa
  double poisson_ratio = 0.0;
  double mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
};

struct TetElement {
  std::array<int, 4> nodes{};
  double volume = 0.0;                    // rest volume (m^3)
  Eigen::Matrix<double, 3, 4> gradients;  // rest gradients of the four shape functions
};

// Throws std::invalid_argument for a degenerate or inverted rest tet.
TetElement make_tet_element(const std::array<Eigen::Vector3d, 4>& rest,
                            const std::array<int, 4>& nodes);

// F = sum_a x_a grad N_a'.
Eigen::Matrix3d deformation_gradient(const TetElement& tet,
                                     const std::array<Eigen::Vector3d, 4>& x);

// Strain in the element's rotated frame: sym(R'F) - I.
Eigen::Matrix3d corotated_strain(const TetElement& tet, const std::array<Eigen::Vector3d, 4>& x,
                                 const Eigen::Matrix3d& rotation);

}  // namespace handlab::sim
