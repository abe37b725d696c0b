// One backward-Euler step of a model's bodies (hand_simulator.h says what it minimises), with
// the solver's memory between steps: the Newton matrix's layout and factorisation, the
// step's terms and contacts. The hand's simulator runs one for the hand and the cube; the free
// cube's stepper runs one of its own for the cube alone (free_cube.h), beside it.
#pragma once

#include <memory>
#include <vector>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/sim_options.h"

namespace handlab::sim {

class StepSolver {
 public:
  // `model` must outlive the solver; `options` as HandSimulator checks them (at least one Newton
  // iteration a pass: std::invalid_argument).
  StepSolver(const HandSimModel& model, const SimOptions& options);
  ~StepSolver();
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  // `result` becomes the state one time step after `start`, towards `targets` (one per bone,
  // checked by the caller). On an exception `result` is unspecified and `start` untouched.
  SimStepReport step(const HandSimState& start, const std::vector<RigidPose>& targets,
                     HandSimState& result);

  // Whether flesh touched the cube in the last step: inside it at the prediction, or carried
  // inside by a pass.
  bool flesh_touched_cube() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace handlab::sim
