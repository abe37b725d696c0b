// The textbook linear co-rotational tetrahedron (Müller & Gross 2004), for tests: the linear
// element's energy measured in the frame of the element's rotation R (from the polar
// decomposition of F),
//   E = 1/2 (R'x - X)' K (R'x - X),   grad = R K (R'x - X),   Hessian ~ R K R' (R held fixed),
// with K the constant 12x12 stiffness of linear elasticity. The simulator's flesh
// (core/sim/flesh_energy.h) computes the same without forming K; this is what it is checked
// against.
#pragma once

#include <array>

#include <Eigen/Core>

#include "core/sim/tet_element.h"

namespace handlab::sim {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// K, node-major (x0 y0 z0 x1 ...).
Matrix12d corotated_stiffness(const TetElement& tet, const Material& material);

struct ElementEvaluation {
  double energy = 0.0;
  Vector12d gradient;
  Matrix12d hessian;  // R K R'
};

// `rotation` is the element's R (see extract_rotation), `rest` its rest node positions.
void evaluate_corotated(const Matrix12d& stiffness, const std::array<Eigen::Vector3d, 4>& rest,
                        const std::array<Eigen::Vector3d, 4>& x, const Eigen::Matrix3d& rotation,
                        ElementEvaluation& out, bool with_hessian = true);

}  // namespace handlab::sim
