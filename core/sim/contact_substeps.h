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

// The substeps a step is taken in: the time step over contact_time_step, to the nearest whole
// number (1: none).
int contact_substep_count(const SimParameters& parameters);

// The window after a contact began: contact_substep_window in steps, opened anew by each step
// that began one, counted down by each step taken in it.
class SubstepWindow {
 public:
  explicit SubstepWindow(const SimParameters& parameters);
  void open() { left_ = steps_; }
  void count_down() { left_ = left_ > 0 ? left_ - 1 : 0; }
  bool open_now() const { return left_ > 0; }

 private:
  int steps_ = 0, left_ = 0;
};

class ContactSubsteps {
 public:
  // On when the parameters ask for a contact time step shorter than the time step, of the
  // whole hand (not contact_substeps_cube).
  static bool enabled(const SimParameters& parameters);

  ContactSubsteps(const HandSimModel& model, const SimOptions& options);
  ContactSubsteps(const ContactSubsteps&) = delete;
  ContactSubsteps& operator=(const ContactSubsteps&) = delete;

  int substeps() const { return substeps_; }
  // Whether a flesh point touches the cube after a step that it did not touch before.
  static bool began_contact(const HandSimState& before, const HandSimState& after);

  void open_window() { window_.open(); }
  void count_down() { window_.count_down(); }
  bool in_window() const { return window_.open_now(); }

  // `start` to `result` in substeps, the targets moved from `from` to `to` (one per bone)
  // along the way. Whether flesh touched the cube in any of them: flesh_touched_cube().
  SimStepReport step(const HandSimState& start, const std::vector<RigidPose>& from,
                     const std::vector<RigidPose>& to, HandSimState& result);
  bool flesh_touched_cube() const { return touched_; }

 private:
  HandSimModel model_;  // the hand's, its time step a substep
  StepSolver solver_;
  int substeps_ = 1;
  SubstepWindow window_;
  bool touched_ = false;
};

}  // namespace handlab::sim
