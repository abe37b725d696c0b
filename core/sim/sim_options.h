// What a step of the soft-hand simulator is asked to do (SimOptions: the Newton and linear
// solves' policy, threads) and what it reports back (SimStepReport): shared by the simulator
// and its stages, so that a stage needs no part of the simulator's own header.
#pragma once

#include <array>
#include <cstddef>

namespace handlab::sim {

struct SimOptions {
  int newton_iterations = 1;
  // The linear solves: conjugate gradients until the residual left would move no unknown on
  // its own by more than linear_tolerance (m or rad), preconditioned by the factorisation of
  // an earlier matrix; when CG has not converged in max_linear_iterations, the matrix is
  // factorised anew and solved directly, and after a converged solve that took more than
  // refactor_iterations the next solve factorises first.
  double linear_tolerance = 1e-8;
  int max_linear_iterations = 6;
  int refactor_iterations = 4;
  // After a step's first solve failed in CG with the previous step's factorisation as its
  // preconditioner (the matrix changes faster than CG follows: tets crossing the stiffening
  // threshold, contacts coming and going), this many steps factorise at their first solve
  // instead of trying CG first.
  int direct_steps = 3;
  // After this many steps in a row whose first solve took two CG iterations or more, the
  // next solve factorises: the preconditioner has drifted (0: never).
  int refresh_steps = 20;
  // CG gives up halfway through max_linear_iterations, and the matrix is factorised, when what
  // is left of the residual would still move an unknown by more than this many times
  // linear_tolerance (0: never).
  double halfway_gap = 1e3;
  // Threads the per-tet work is split over. Results depend on it (the order forces are
  // summed in) but on nothing else: the same inputs and thread count give the same states.
  int threads = 2;
};

// The options of the small solvers beside the hand's (the free cube's, the cube's substeps'):
// a few dozen unknowns at most, on one thread.
inline SimOptions single_threaded() {
  SimOptions o;
  o.threads = 1;
  return o;
}

// The parts of a step's solve whose wall time a step reports (SimStepReport::timer_ms), as
// MuJoCo's timers do: the energy's terms at each Newton iterate, the line search's energies,
// the Newton matrix written into the factorisation's panels, their factorisation, CG's
// iterations (its products, preconditioner solves and the diagonal it measures by), and the
// solves by a factor alone. What a step spends elsewhere is its time less their sum: the
// prediction, the contact search, the friction's checks, the factor's update for the cube's
// own terms, and the cube's substeps and free steps (whose own solves are not counted here).
enum class StepTimer { kEvaluate, kLineSearch, kAssemble, kFactorize, kCg, kDirectSolve, kCount };
constexpr std::size_t kStepTimers = std::size_t(StepTimer::kCount);
// Each timer's name in reports (JSON keys, CSV columns) and for people, in StepTimer's order.
constexpr auto kStepTimerNames = std::to_array<const char*>(
    {"evaluate", "line_search", "assemble", "factorize", "cg", "direct_solve"});
constexpr auto kStepTimerLabels = std::to_array<const char*>(
    {"evaluate", "line search", "assemble", "factorise", "CG", "direct solve"});
static_assert(kStepTimerNames.size() == kStepTimers && kStepTimerLabels.size() == kStepTimers);

struct SimStepReport {
  int newton_iterations = 0;
  int linear_iterations = 0;  // CG iterations (a direct solve counts one)
  int factorizations = 0;     // numeric factorisations of the Newton matrix
  // Solves by the factorisation alone (after a factorisation, and in a step's later passes
  // while the factor is the matrix's): each counts one linear iteration, and needs no product.
  int direct_solves = 0;
  // CG solves that stopped short of the tolerance (out of iterations, far off halfway, or a
  // direction of no positive curvature), each then factorised and solved directly: the CG
  // iterations they took were spent for nothing.
  int failed_cg = 0;
  // Step lengths the line search rejected (each halves the next; after 12 the last is taken).
  // With an energy and gradient that agree, rare: a step that runs into a surface or a kink.
  int halvings = 0;
  int contacts = 0;              // active contact points (hand-cube, hand-floor, cube-floor)
  double max_penetration = 0.0;  // m, deepest flesh node inside the cube after the step
  double residual = 0.0;         // max |gradient| where the last Newton solve started (N)
  std::array<double, kStepTimers> timer_ms{};  // wall time by StepTimer (ms)
};

// A step solved more than once (again in substeps): the work of each added up, the result's
// penetration and residual the last's.
inline void add_work(const SimStepReport& more, SimStepReport& total) {
  total.newton_iterations += more.newton_iterations;
  total.linear_iterations += more.linear_iterations;
  total.factorizations += more.factorizations;
  total.direct_solves += more.direct_solves;
  total.failed_cg += more.failed_cg;
  total.halvings += more.halvings;
  for (std::size_t k = 0; k < kStepTimers; ++k) total.timer_ms[k] += more.timer_ms[k];
  total.max_penetration = more.max_penetration;
  total.residual = more.residual;
}

}  // namespace handlab::sim
