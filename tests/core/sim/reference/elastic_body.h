// For tests: a deformable body of textbook linear co-rotational tetrahedra (corotated_element.h)
// with an assembled Newton matrix and Eigen's LDLT, as an immutable model and a state that a
// backward-Euler step advances: the reference the soft-hand simulator's flesh was built from,
// checked against the patch test and beam theory. Energies:
// elasticity, gravity, zero-length springs pulling nodes towards anchor points (the coupling
// and tracking springs' form), and nodes held fixed.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/mesh/tet_mesh.h"
#include "core/sim/tet_element.h"
#include "tests/core/sim/reference/corotated_element.h"

namespace handlab::sim {

struct AnchorSpring {
  int node = 0;
  double stiffness = 0.0;  // N/m
};

struct ElasticBodyModel {
  std::vector<Eigen::Vector3d> rest;  // node positions at rest (m)
  std::vector<TetElement> tets;
  std::vector<Matrix12d> stiffness;   // per tet
  std::vector<double> mass;           // lumped, per node (kg)
  std::vector<bool> fixed;            // nodes held where the state puts them
  std::vector<AnchorSpring> springs;  // towards the anchors given to each step
  Eigen::Vector3d gravity = Eigen::Vector3d(0, -9.81, 0);
  double time_step = 1.0 / 120.0;  // s
};

// Lumped masses from the density; no node fixed, no springs.
ElasticBodyModel make_elastic_body(const mesh::TetMesh& mesh, const Material& material,
                                   double density);

struct ElasticBodyState {
  std::vector<Eigen::Vector3d> position, velocity;
  std::vector<Eigen::Quaterniond> rotation;  // per tet: warm start of the rotation extraction
};

ElasticBodyState rest_state(const ElasticBodyModel& model);

struct StepReport {
  int newton_iterations = 0;
  // max |gradient| at free nodes (N) where the last Newton solve started (for a static
  // solve that stopped converged: at the solution)
  double residual = 0.0;
};

// Newton on the backward-Euler energy E(x) = 1/(2h^2) |x - x_pred|_M^2 + U(x), or on U(x)
// alone for a static equilibrium. The sparsity pattern and the symbolic factorisation are
// made once, for the model it is built with.
class ElasticBodySolver {
 public:
  explicit ElasticBodySolver(const ElasticBodyModel& model);
  ~ElasticBodySolver();

  // One time step; `anchors` has one point per model spring.
  StepReport step(ElasticBodyState& state, const std::vector<Eigen::Vector3d>& anchors,
                  int newton_iterations = 1);
  // Static equilibrium under `forces` (per node, N) in addition to gravity; velocities zero.
  StepReport solve_static(ElasticBodyState& state, const std::vector<Eigen::Vector3d>& anchors,
                          const std::vector<Eigen::Vector3d>& forces, int max_iterations = 20,
                          double tolerance = 1e-10);

  // The potential U (elastic + gravity + springs - forces . x) and its gradient, with the
  // element rotations updated from the state (for tests).
  double potential(ElasticBodyState& state, const std::vector<Eigen::Vector3d>& anchors,
                   Eigen::VectorXd* gradient) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace handlab::sim
