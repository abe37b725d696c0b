// The Newton increment: preconditioned conjugate gradients on the matrix held as its terms,
// with the factorisation of an earlier matrix as the preconditioner (a step's matrix changes
// slowly: element rotations, contacts coming and going), factorised anew when CG would need
// more than a few iterations; where the factor is the matrix's own, a direct solve. The policy
// and its reasons are in docs/simulator.md, its measured costs in docs/performance.md.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/sim/hand_sim_model.h"
#include "core/sim/newton_matrix.h"
#include "core/sim/newton_terms.h"
#include "core/sim/supernodal_ldlt.h"
#include "core/sim/thread_pool.h"

namespace handlab::sim {

struct SimOptions;
struct SimStepReport;

// What the solver carries from solve to solve and step to step: the factorisation of the last
// matrix it factorised, what that matrix was, and the policy's counters. A step's result
// depends on it as well as on the state and the targets (a solve by CG stops within the
// tolerance, not at the exact answer), so HandSimulator owns it and documents it as an input.
struct SolverMemory {
  SupernodalLdlt factor;  // its structure fixed by the model, its values the last matrix's
  bool factorized = false;
  bool stale = false;  // the last CG took more than refactor_iterations: factorise next
  // Steps taken, the step of the last factorisation, and the step before which a step's first
  // solve factorises at once.
  long step = 0, factorized_at = -1, direct_until = 0;
  int solves_this_step = 0;
  int slow_steps = 0;       // consecutive steps whose first solve took two CG iterations or more
  int last_iterations = 0;  // CG's in this step's last solve
  // Evaluations that found the kept terms anew (counted by the caller), and which of them the
  // factor is of; the contact terms on other unknowns than the cube's that it holds.
  long terms_found = 0, factorized_terms = -1;
  std::vector<SpringTerm> factorized_contacts;
  // The cube's unknowns; whether the ordering put them last (its many contact candidates make
  // them dense rows), so that the factor's last block can follow the cube's own terms
  // (SupernodalLdlt::modify_trailing); those terms when the matrix was factorised, and the
  // change since that the factor has taken.
  std::vector<int> cube_dofs;
  bool cube_trailing = false;
  Matrix6d cube_factorized = Matrix6d::Zero(), cube_applied = Matrix6d::Zero();
  Eigen::VectorXd product_scratch;  // the second worker's part of a CG product
};

// The factorisation's structure for the model's Newton matrix, and where its blocks go.
void analyze_newton_matrix(const HandSimModel& model, SolverMemory& memory, NewtonLayout& layout);

// The increment of a model whose nodes are kinematic (HandSimModel::kinematic_nodes) and that
// has no bones: the cube's six unknowns alone, from its block of the matrix; zero elsewhere.
Eigen::VectorXd solve_cube_step(const HandSimModel& model, const NewtonTerms& terms,
                                SimStepReport& report);

// Solves A dq = -gradient for the terms' matrix; counts into `report`.
Eigen::VectorXd solve_newton_step(const HandSimModel& model, const NewtonTerms& terms,
                                  const NewtonLayout& layout, NewtonDiagonal& diagonal_cache,
                                  const SimOptions& options, ThreadPool& pool, SolverMemory& memory,
                                  SimStepReport& report);

}  // namespace handlab::sim
