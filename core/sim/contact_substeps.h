// A step in which flesh first touches the cube is taken again in substeps, and so are the
// steps for a while after it (SimParameters::contact_time_step, contact_substep_window). The
// light cube's outcome turns on how its first contacts are integrated: the pad's first push
// launches a half-gram cube within a step (docs/simulator.md, "Levers screened on that map").
// The energies are the model's; only the integration of those steps is finer, the targets
// moved between the step's start and end along the way.
#pragma once

#include <vector>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/sim_options.h"
#include "core/sim/step_solver.h"

namespace handlab::sim {

class ContactSubsteps {
 public:
  // On when the parameters ask for a contact time step shorter than the time step.
  static bool enabled(const SimParameters& parameters);

  ContactSubsteps(const HandSimModel& model, const SimOptions& options);
  ContactSubsteps(const ContactSubsteps&) = delete;
  ContactSubsteps& operator=(const ContactSubsteps&) = delete;

  int substeps() const { return substeps_; }
  // Whether a flesh point touches the cube after a step that it did not touch before.
  static bool began_contact(const HandSimState& before, const HandSimState& after);
  // Whether the next step falls in the window after a contact began.
  bool in_window() const { return window_left_ > 0; }
  // Whether flesh touched the cube in the last substep.
  bool flesh_touched_cube() const { return solver_.flesh_touched_cube(); }

  // `start` to `result` in substeps, the targets moved from `from` to `to` (one per bone)
  // along the way; `began` opens the window anew, else the step counts down within it.
  SimStepReport step(const HandSimState& start, const std::vector<RigidPose>& from,
                     const std::vector<RigidPose>& to, bool began, HandSimState& result);

 private:
  HandSimModel model_;  // the hand's, its time step a substep
  StepSolver solver_;
  int substeps_ = 1, window_steps_ = 0, window_left_ = 0;
};

}  // namespace handlab::sim
