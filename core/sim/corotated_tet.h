// Linear co-rotational elasticity of one linear tetrahedron (Müller & Gross 2004, as in
// Verschoor et al. 2018): the linear element's energy measured in the frame of the element's
// rotation R (from the polar decomposition of F),
//   E = 1/2 (R'x - X)' K (R'x - X),   grad = R K (R'x - X),   Hessian ~ R K R' (R held fixed),
// with K the constant 12x12 stiffness of linear elasticity. R K R' is positive semidefinite
// whatever the deformation, so Newton's systems stay positive definite.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace handlab::sim {

struct Material {
  double youngs_modulus = 0.0;  // Pa
  double poisson_ratio = 0.0;
  double mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
};

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

struct TetElement {
  std::array<int, 4> nodes{};
  double volume = 0.0;                    // rest volume (m^3)
  Eigen::Matrix<double, 3, 4> gradients;  // rest gradients of the four shape functions
  Matrix12d stiffness;                    // K, node-major (x0 y0 z0 x1 ...)
};

// Throws std::invalid_argument for a degenerate or inverted rest tet.
TetElement make_tet_element(const std::array<Eigen::Vector3d, 4>& rest,
                            const std::array<int, 4>& nodes, const Material& material);

// F = sum_a x_a grad N_a'.
Eigen::Matrix3d deformation_gradient(const TetElement& tet,
                                     const std::array<Eigen::Vector3d, 4>& x);

// Strain in the element's rotated frame: sym(R'F) - I.
Eigen::Matrix3d corotated_strain(const TetElement& tet, const std::array<Eigen::Vector3d, 4>& x,
                                 const Eigen::Matrix3d& rotation);

struct ElementEvaluation {
  double energy = 0.0;
  Vector12d gradient;
  Matrix12d hessian;  // R K R'
};

// `rotation` is the element's R (see extract_rotation), `rest` its rest node positions.
void evaluate_corotated(const TetElement& tet, const std::array<Eigen::Vector3d, 4>& rest,
                        const std::array<Eigen::Vector3d, 4>& x, const Eigen::Matrix3d& rotation,
                        ElementEvaluation& out, bool with_hessian = true);

}  // namespace handlab::sim
