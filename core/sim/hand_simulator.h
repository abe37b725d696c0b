// One backward-Euler step of the soft hand and the cube: every energy of the model (flesh,
// stiffening, joints, coupling, tracking, contact and friction, gravity) summed with the
// kinetic term into E(q) = 1/(2h^2) |q - q_pred|^2_M + U(q), minimised by Newton (one
// iteration by default, as Verschoor et al. do). Contacts are found at the predicted state;
// after the step each friction anchor sticks, or slides to the edge of Coulomb's cone. The
// stages are in their own files; hand_simulator.cpp lists them, docs/simulator.md explains
// them.
#pragma once

#include <memory>
#include <vector>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"

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

struct SimStepReport {
  int newton_iterations = 0;
  int linear_iterations = 0;  // CG iterations (a direct solve counts one)
  int factorizations = 0;     // numeric factorisations of the Newton matrix
  // Solves by the factorisation alone (after a factorisation, and in a step's later passes
  // while the factor is the matrix's): each counts one linear iteration, and needs no product.
  int direct_solves = 0;
  // Step lengths the line search rejected (each halves the next; after 12 the last is taken).
  // With an energy and gradient that agree, rare: a step that runs into a surface or a kink.
  int halvings = 0;
  int contacts = 0;              // active contact points (hand-cube, hand-floor, cube-floor)
  double max_penetration = 0.0;  // m, deepest flesh node inside the cube after the step
  double residual = 0.0;         // max |gradient| where the last Newton solve started (N)
};

class HandSimulator {
 public:
  explicit HandSimulator(const HandSimModel& model, SimOptions options = {});
  ~HandSimulator();
  HandSimulator(const HandSimulator&) = delete;
  HandSimulator& operator=(const HandSimulator&) = delete;

  // Advances `state` by one time step towards the bones' targets (one per bone, centres of
  // mass: see bone_targets). A target that is not finite, or of another hand, is rejected
  // with std::invalid_argument, and on any exception the state is left as it was.
  // Besides the model, the state and the targets, the step reads the solver's memory that the
  // simulator keeps from its earlier steps (SolverMemory in linear_solve.h: the factorisation
  // of an earlier Newton matrix that preconditions CG, its age and the policy's counters).
  // CG stops within a tolerance, so the results depend on that memory within the tolerance,
  // and bit for bit on the steps taken before: the same simulator options, the same sequence
  // of states and targets from construction, give the same states.
  SimStepReport step(HandSimState& state, const std::vector<RigidPose>& targets);

  const HandSimModel& model() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace handlab::sim
