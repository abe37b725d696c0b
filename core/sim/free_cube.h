// A cube that no flesh touches, not resting, is stepped alone in substeps. On the half-gram 1 cm
// cube a corner's floor contact (10^4 N/m) rings 75 times faster than a 1/120 s step resolves:
// stepped with the hand, a cube the fingers had let go hopped and skated on by itself, gaining
// energy (`sim settle`: up to 187 mm beyond what its energy allows). In 32 substeps it settles
// as its energy allows (docs/simulator.md, "Solver"). The energies are the model's; only the
// cube's integration is finer, and only while nothing but the floor acts on it.
#pragma once

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/step_solver.h"

namespace handlab::sim {

class FreeCubeStepper {
 public:
  static constexpr int kSubsteps = 32;
  static constexpr int kNewtonIterations = 3;  // a substep's (free_cube.cpp)

  explicit FreeCubeStepper(const SimParameters& parameters);
  FreeCubeStepper(const FreeCubeStepper&) = delete;
  FreeCubeStepper& operator=(const FreeCubeStepper&) = delete;

  // Whether the cube of `state` lies still on four corners: slower than 1 mm/s and 0.1 rad/s.
  static bool resting(const HandSimState& state);

  // Whether the cube of a step from `start` is free and not resting: no flesh touched it in the
  // step (`flesh_touching`: inside it at the prediction or in a pass), and it did not lie still
  // on four corners at the start.
  static bool applies(const HandSimState& start, bool flesh_touching);

  // The cube's pose, velocity and floor anchors in `result` taken again from `start` in
  // kSubsteps steps of the cube alone.
  void step(const HandSimState& start, HandSimState& result);

 private:
  HandSimModel model_;  // the cube and the floor alone, its time step a substep
  StepSolver solver_;   // one thread, kNewtonIterations: six unknowns
};

}  // namespace handlab::sim
