// One backward-Euler step of the soft hand and the cube: every energy of the model (flesh,
// stiffening, joints, coupling, tracking, contact, its damping and friction, gravity) summed with
// the kinetic term into E(q) = 1/(2h^2) |q - q_pred|^2_M + U(q), minimised by Newton (one iteration
// by default, as Verschoor et al. do). Contacts are found at the predicted state; after the step
// each friction anchor sticks, or slides to the edge of Coulomb's cone; a cube that no flesh
// touches and that is not resting is stepped again alone, in substeps (free_cube.h); where the
// parameters ask for it, a step in which flesh begins to touch the cube, and the steps for a while
// after, are taken in substeps, of the whole hand (contact_substeps.h) or of the cube alone against
// the flesh's path (cube_substeps.h). The stages are in their own files; step_solver.cpp lists
// them, docs/simulator.md explains them.
#pragma once

#include <memory>
#include <vector>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/sim_options.h"

namespace handlab::sim {

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
  // of an earlier Newton matrix that preconditions CG, its age and the policy's counters; with
  // contact substeps, the substeps' own, the last step's targets and the window left, or the
  // cube's substeps' set of flesh points and its solver).
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
