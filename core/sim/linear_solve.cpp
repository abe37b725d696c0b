#include "core/sim/linear_solve.h"

#include <stdexcept>

#include <Eigen/Cholesky>

#include "core/sim/sim_options.h"
#include "core/sim/step_timer.h"

namespace handlab::sim {

void analyze_newton_matrix(const HandSimModel& model, SolverMemory& memory, NewtonLayout& layout) {
  // The structure (the ordering, L's pattern, the panels and where the matrix's blocks go in
  // them) from Eigen's factorisation of a matrix of the pattern, diagonally dominant so that it
  // is positive definite.
  Eigen::SparseMatrix<double> matrix = newton_pattern(model);
  const int* outer = matrix.outerIndexPtr();
  const int* inner = matrix.innerIndexPtr();
  for (int col = 0; col < matrix.cols(); ++col)
    for (int v = outer[col]; v < outer[col + 1]; ++v)
      matrix.valuePtr()[v] = inner[v] == col ? double(outer[col + 1] - outer[col]) : 1.0;
  const SupernodalLdlt::Factor structure(matrix);
  if (structure.info() != Eigen::Success)
    throw std::logic_error("HandSimulator: no factorisation of the Newton matrix's pattern");
  memory.factor.analyze(structure, matrix);
  layout = make_newton_layout(model, memory.factor);
  memory.cube_dofs.clear();
  for (int k = 0; k < 6; ++k) memory.cube_dofs.push_back(3 * cube_block(model) + k);
  memory.cube_trailing = memory.factor.trailing(memory.cube_dofs);
}

Eigen::VectorXd solve_cube_step(const HandSimModel& model, const NewtonTerms& terms,
                                SimStepReport& report) {
  const ScopedStepTimer timer(report, StepTimer::kDirectSolve);
  const int cube = 3 * cube_block(model);
  const Eigen::LDLT<Matrix6d> ldlt(cube_block_matrix(model, terms));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
    throw std::runtime_error("HandSimulator: the cube's Newton system is not positive definite");
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(terms.gradient.size());
  dq.segment<6>(cube) = ldlt.solve(-terms.gradient.segment<6>(cube));
  ++report.linear_iterations;
  ++report.direct_solves;
  return dq;
}

Eigen::VectorXd solve_newton_step(const HandSimModel& model, const NewtonTerms& terms,
                                  const NewtonLayout& layout, NewtonDiagonal& diagonal_cache,
                                  const SimOptions& options, ThreadPool& pool, SolverMemory& memory,
                                  SimStepReport& report) {
  SupernodalLdlt& factor = memory.factor;
  const Eigen::VectorXd rhs = -terms.gradient;
  auto refactor = [&] {
    double* values = factor.values();
    {
      const ScopedStepTimer timer(report, StepTimer::kAssemble);
      if (pool.workers() >= 2 && layout.panel_split > 0) {
        pool.run([&](int worker) {
          if (worker > 1) return;
          const int begin = worker == 0 ? 0 : layout.panel_split;
          const int end = worker == 0 ? layout.panel_split : factor.value_count();
          std::fill(values + begin, values + end, 0.0);
          write_panels(model, terms, layout, factor, values, worker);
        });
      } else {
        factor.clear_values();
        write_panels(model, terms, layout, factor, values);
      }
    }
    bool definite = false;
    {
      const ScopedStepTimer timer(report, StepTimer::kFactorize);
      definite = factor.factorize_values(&pool);
    }
    if (!definite)
      throw std::runtime_error("HandSimulator: the Newton system is not positive definite");
    memory.factorized = true;
    memory.cube_factorized = cube_matrix(model, terms);
    memory.cube_applied.setZero();
    memory.factorized_terms = memory.terms_found;
    other_contacts(model, terms, memory.factorized_contacts);
    memory.factorized_at = memory.step;
    memory.slow_steps = 0;
    ++report.factorizations;
  };
  // A solve by the factor alone.
  auto solve_by_factor = [&] {
    const ScopedStepTimer timer(report, StepTimer::kDirectSolve);
    ++report.linear_iterations;
    ++report.direct_solves;
    return factor.solve(rhs, &pool);
  };
  // A direct solve with the matrix factorised anew, whose factorisation then preconditions
  // the next solves.
  auto direct = [&] {
    refactor();
    memory.stale = false;
    memory.last_iterations = 0;
    return solve_by_factor();
  };
  const bool first = memory.solves_this_step++ == 0;
  // A later pass (another contact state from the same start) whose pass before needed more
  // than half of CG's iterations factorises at once: the passes after it then solve
  // directly, where each would take as many iterations again.
  const bool slow_pass = !first && 2 * memory.last_iterations > options.max_linear_iterations;
  memory.last_iterations = 0;
  if (!memory.factorized || memory.stale || slow_pass ||
      (first && memory.step < memory.direct_until))
    return direct();
  // Whether the factor is still the matrix itself, up to the cube's own terms: the kept terms
  // have not been found anew since it was factorised, and the contact terms on other unknowns
  // than the cube's alone are the same. A step's later passes differ from its first in their
  // contacts only, mostly the floor's corners: after a factorisation they then solve directly.
  bool exact = memory.factorized_terms == memory.terms_found &&
               same_other_contacts(model, terms, memory.factorized_contacts);
  // The cube's own terms (the floor's contacts with its corners come and go, stick and slide)
  // change the matrix on the cube's unknowns alone; ordered last, they are the factor's last
  // block, which takes the change exactly for the cost of a 6x6 factorisation.
  if (memory.cube_trailing) {
    const Matrix6d change = cube_matrix(model, terms) - memory.cube_factorized;
    if (change != memory.cube_applied && factor.modify_trailing(memory.cube_dofs, change))
      memory.cube_applied = change;
    exact = exact && memory.cube_applied == change;
  } else {
    exact = exact && cube_matrix(model, terms) == memory.cube_factorized;
  }
  if (exact) return solve_by_factor();
  // Converged when what is left of the residual would move no unknown, on its own, by more
  // than the tolerance: a criterion per unknown, because a relative norm is the flesh's and
  // lets a light cube's unknowns go unsolved.
  ScopedStepTimer cg_timer(report, StepTimer::kCg);
  const Eigen::VectorXd inverse_diagonal = diagonal(model, terms, diagonal_cache).cwiseInverse();
  auto left = [&](const Eigen::VectorXd& residual) {  // the largest move it would make
    return (residual.cwiseProduct(inverse_diagonal)).lpNorm<Eigen::Infinity>();
  };
  auto converged = [&](const Eigen::VectorXd& residual) {
    return left(residual) <= options.linear_tolerance;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rhs.size()), r = rhs, z = factor.solve(r, &pool),
                  direction = z, product;
  double rz = r.dot(z);
  int iterations = 0;
  bool done = converged(r);
  while (!done && iterations < options.max_linear_iterations) {
    multiply(model, terms, direction, product, &pool, &memory.product_scratch);
    const double curvature = direction.dot(product);
    if (!(curvature > 0)) break;
    const double alpha = rz / curvature;
    x += alpha * direction;
    r -= alpha * product;
    ++iterations;
    // The next direction only for a next iteration: its solve is an iteration's larger cost.
    done = converged(r);
    if (done || iterations == options.max_linear_iterations) break;
    // Halfway and still far (the preconditioner is too far from the matrix): the iterations
    // left rarely close the gap, and the factorisation will be needed.
    if (options.halfway_gap > 0 && iterations == (options.max_linear_iterations + 1) / 2 &&
        left(r) > options.halfway_gap * options.linear_tolerance)
      break;
    z = factor.solve(r, &pool);
    const double rz_next = r.dot(z);
    direction = z + (rz_next / rz) * direction;
    rz = rz_next;
  }
  cg_timer.stop();
  report.linear_iterations += iterations;
  memory.stale = iterations > options.refactor_iterations;
  memory.last_iterations = iterations;
  if (first) {
    // A preconditioner that has drifted from the matrix, if not enough to fail CG: renewed
    // after refresh_steps steps in a row that needed two iterations or more.
    memory.slow_steps = iterations >= 2 ? memory.slow_steps + 1 : 0;
    if (options.refresh_steps > 0 && memory.slow_steps >= options.refresh_steps) {
      memory.stale = true;
      memory.slow_steps = 0;
    }
  }
  if (!done) {
    // CG did not converge with this preconditioner: factorise the matrix itself. If the
    // preconditioner was the previous step's matrix, the matrix is changing faster than CG
    // follows (tets crossing the stiffening threshold, contacts coming and going): the next
    // steps factorise at once rather than spend CG iterations first.
    if (first && memory.factorized_at == memory.step - 1)
      memory.direct_until = memory.step + 1 + options.direct_steps;
    ++report.failed_cg;
    return direct();
  }
  return x;
}

}  // namespace handlab::sim
