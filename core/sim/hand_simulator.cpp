// The step as solvers side by side: the hand's and the cube's together (step_solver.h), taken
// again in substeps where flesh begins to touch the cube when the parameters ask for it, the
// whole hand (contact_substeps.h) or the cube alone against the flesh's path (cube_substeps.h),
// then, for a cube that no flesh touches and that is not resting, the cube alone again in
// substeps (free_cube.h).
#include "core/sim/hand_simulator.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/sim/contact_substeps.h"
#include "core/sim/cube_substeps.h"
#include "core/sim/free_cube.h"
#include "core/sim/step_solver.h"

namespace handlab::sim {
namespace {

const SimOptions& checked(const SimOptions& options) {
  if (options.newton_iterations < 1)
    throw std::invalid_argument("HandSimulator: at least one Newton iteration a step");
  if (options.threads < 1) throw std::invalid_argument("HandSimulator: at least one thread");
  return options;
}

void check_targets(const HandSimModel& model, const std::vector<RigidPose>& targets) {
  if (int(targets.size()) != model.bone_count())
    throw std::invalid_argument("HandSimulator::step: one target per bone");
  for (const RigidPose& t : targets)
    if (!t.position.allFinite() || !t.rotation.coeffs().allFinite() ||
        std::abs(t.rotation.norm() - 1.0) > 1e-6)
      throw std::invalid_argument("HandSimulator::step: a target that is not a finite pose");
}

int contact_count(const HandSimState& s) {
  return int(s.node_cube.size() + s.sample_cube.size() + s.node_floor.size() +
             s.corner_floor.size());
}

}  // namespace

struct HandSimulator::Impl {
  const HandSimModel& model;
  StepSolver solver;
  std::unique_ptr<FreeCubeStepper> free_cube;   // made when first needed (a hand's model only)
  std::unique_ptr<ContactSubsteps> substeps;    // when the parameters ask for them
  std::vector<RigidPose> last_targets;          // the step before's, where substeps start
  std::unique_ptr<CubeSubsteps> cube_substeps;  // or for these, with their window
  SubstepWindow cube_window;
  HandSimState next;  // the step's result, swapped with the state: its buffers are reused

  Impl(const HandSimModel& m, const SimOptions& o)
      : model(m), solver(m, o), cube_window(m.parameters) {
    if (m.node_count() > 0 && ContactSubsteps::enabled(m.parameters))
      substeps = std::make_unique<ContactSubsteps>(m, o);
    if (m.node_count() > 0 && CubeSubsteps::enabled(m.parameters))
      cube_substeps = std::make_unique<CubeSubsteps>(m);
  }

  // The cube of a step that began a contact, and of the window's steps after, taken again;
  // with cube_substeps_on_floor, also where flesh touches it as it moves on the floor.
  void substep_cube(const HandSimState& start, HandSimState& result, bool flesh_touched,
                    SimStepReport& report) {
    const bool began = ContactSubsteps::began_contact(start, result);
    const bool on_floor = model.parameters.cube_substeps_on_floor && flesh_touched &&
                          !start.corner_floor.empty() && !FreeCubeStepper::resting(start);
    const bool in_window = cube_window.open_now() || began || on_floor;
    cube_window.count_down();
    if (began) cube_window.open();
    if (in_window) report.max_penetration = cube_substeps->step(start, result).max_penetration;
  }
};

HandSimulator::HandSimulator(const HandSimModel& model, SimOptions options)
    : impl_(std::make_unique<Impl>(model, checked(options))) {}
HandSimulator::~HandSimulator() = default;
const HandSimModel& HandSimulator::model() const {
  return impl_->model;
}

SimStepReport HandSimulator::step(HandSimState& state, const std::vector<RigidPose>& targets) {
  Impl& sim = *impl_;
  check_targets(sim.model, targets);
  HandSimState& next = sim.next;
  SimStepReport report;
  bool flesh_touched = false;
  ContactSubsteps* substeps = sim.substeps.get();
  const std::vector<RigidPose>& from = sim.last_targets.empty() ? targets : sim.last_targets;
  if (substeps && substeps->in_window()) {
    report = substeps->step(state, from, targets, next);
    flesh_touched = substeps->flesh_touched_cube();
    substeps->count_down();
    if (ContactSubsteps::began_contact(state, next)) substeps->open_window();
  } else {
    report = sim.solver.step(state, targets, next);
    flesh_touched = sim.solver.flesh_touched_cube();
    if (substeps && ContactSubsteps::began_contact(state, next)) {
      add_work(substeps->step(state, from, targets, next), report);
      flesh_touched = substeps->flesh_touched_cube();
      substeps->open_window();
    }
  }
  if (substeps) sim.last_targets = targets;
  if (sim.cube_substeps) sim.substep_cube(state, next, flesh_touched, report);
  if (sim.model.node_count() > 0 && FreeCubeStepper::applies(state, flesh_touched)) {
    if (!sim.free_cube) sim.free_cube = std::make_unique<FreeCubeStepper>(sim.model.parameters);
    sim.free_cube->step(state, next);
  }
  report.contacts = contact_count(next);
  std::swap(state, next);
  return report;
}

}  // namespace handlab::sim
