// The step as a list of stages, each in its own file: predict; find contacts (contact.h); in
// up to kFrictionPasses passes, evaluate the energy (flesh_energy.h, body_energies.h,
// contact.h, contact_damping.h) into the Newton terms (newton_terms.h), solve for the increment
// (linear_solve.h), search along it, and check the contacts the pass assumed (contact.h);
// velocities; friction anchors for the next step.
#include "core/sim/step_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/sim/body_energies.h"
#include "core/sim/contact.h"
#include "core/sim/contact_damping.h"
#include "core/sim/flesh_energy.h"
#include "core/sim/increment.h"
#include "core/sim/linear_solve.h"
#include "core/sim/newton_matrix.h"
#include "core/sim/newton_terms.h"
#include "core/sim/step_timer.h"
#include "core/sim/thread_pool.h"

namespace handlab::sim {

// Where the step's Newton iterations are: the state and each body's rotation vector since the
// step began (bones, then the cube). Outside the anonymous namespace: StepSolver::Impl holds
// three.
struct StepIterate {
  HandSimState state;
  std::vector<Eigen::Vector3d> turned;
};

namespace {

// How many times a step is taken again when its result disagrees with the contacts it
// assumed (a point that entered a surface unseen, a slide that stopped, a stick that left the
// cone).
constexpr int kFrictionPasses = 4;
// The largest rotation of a body in one Newton iteration (rad).
constexpr double kMaxTurn = 0.25;
// The Newton iterations a pass takes beyond SimOptions::newton_iterations while its steps stop
// short and no flesh touches anything (SimParameters::short_step_excess): with one more at most,
// three of the held poses that docs/simulator.md measures ("The short step's iterations") still
// cycle; with two, none does.
constexpr int kShortStepIterations = 2;

// Whether an iteration, from energy `before` to `after` at `length` along the Newton direction
// dq, stopped short of the step's minimum: the energy fell by more than 1 + `excess` times its
// quadratic model's decrease, -slope (L - L^2 / 2) with H dq = -g and slope = g.dq < 0 (the
// matrix held curvature the energy has not). A fall short of the model's is curvature the model
// has not (contacts), the line search's business.
bool stopped_short(double excess, double before, double after, double slope, double length) {
  return (after - before) / (slope * (length - 0.5 * length * length)) > 1 + excess;
}

// Whether any flesh point touches the cube or the floor: inside at the prediction, or carried
// inside by an earlier pass of this step (`curved` marks both). A pass where flesh touches takes
// SimOptions::newton_iterations as without the short step's iterations: there a grip is held or
// lost by the solver's path, and iterating again lost the scripted light pinch without a squeeze
// (docs/simulator.md, "The short step's iterations"). The cube's corners on the floor do not
// count: the cube alone, in the hand's step or its own substeps, iterates again as the free flesh.
bool flesh_in_contact(const std::vector<Contact>& contacts) {
  return std::any_of(contacts.begin(), contacts.end(),
                     [](const Contact& c) { return c.kind != Contact::kCornerFloor && c.curved; });
}

// Every body carried on by its velocity, into `it` (whose buffers are reused).
void predict(const HandSimModel& model, const HandSimState& start, StepIterate& it) {
  const double h = model.parameters.time_step;
  it.state = start;
  it.turned.resize(std::size_t(model.bone_count() + 1));
  HandSimState& s = it.state;
  for (int n = 0; n < model.node_count(); ++n)
    s.node_position[std::size_t(n)] += h * s.node_velocity[std::size_t(n)];
  auto carry = [&](RigidPose& pose, const RigidVelocity& v, Eigen::Vector3d& rotated) {
    pose.position += h * v.linear;
    rotated = h * v.angular;
    pose.rotation = (rotation_from_vector(rotated) * pose.rotation).normalized();
  };
  for (int b = 0; b < model.bone_count(); ++b)
    carry(s.bone_pose[std::size_t(b)], s.bone_velocity[std::size_t(b)], it.turned[std::size_t(b)]);
  carry(s.cube_pose, s.cube_velocity, it.turned.back());
}

// The longest step along dq that no body turns by more than kMaxTurn in: the linearisation of
// a rotation holds over a fraction of a radian, and a cube, symmetric under quarter turns, can
// lower the energy by a turn of several radians that no physical step takes.
double turn_limited_length(const HandSimModel& model, const Eigen::VectorXd& dq) {
  double largest_turn = 0.0;
  for (int b = 0; b <= model.bone_count(); ++b)
    largest_turn = std::max(largest_turn, dq.segment<3>(3 * (bone_block(model, b) + 1)).norm());
  return largest_turn > kMaxTurn ? kMaxTurn / largest_turn : 1.0;
}

// Velocities from the step taken.
void finish(const HandSimModel& model, const HandSimState& start, StepIterate& it) {
  const double h = model.parameters.time_step;
  HandSimState& s = it.state;
  for (int n = 0; n < model.node_count(); ++n)
    s.node_velocity[std::size_t(n)] =
        (s.node_position[std::size_t(n)] - start.node_position[std::size_t(n)]) / h;
  for (int b = 0; b < model.bone_count(); ++b) {
    s.bone_velocity[std::size_t(b)].linear =
        (s.bone_pose[std::size_t(b)].position - start.bone_pose[std::size_t(b)].position) / h;
    s.bone_velocity[std::size_t(b)].angular = it.turned[std::size_t(b)] / h;
  }
  s.cube_velocity.linear = (s.cube_pose.position - start.cube_pose.position) / h;
  // A cube that turned by more than kMaxTurn in the step spins faster than a step resolves:
  // carried on, its next prediction would turn it by a good part of a quarter turn, where its
  // contacts alias (the corners that touch the floor change places unseen) and the floor
  // pushes it on instead of braking it. Its spin is bounded by kMaxTurn a step (30 rad/s at
  // 120 Hz; game engines bound it likewise, Unity's default at 50 rad/s).
  const double turn = it.turned.back().norm();
  s.cube_velocity.angular = (turn > kMaxTurn ? kMaxTurn / turn : 1.0) * it.turned.back() / h;
  s.time = start.time + h;
}

}  // namespace

struct StepSolver::Impl {
  const HandSimModel& model;
  SimOptions options;
  ThreadPool pool;
  NewtonLayout layout;
  SolverMemory memory;
  // Within a step: the terms of the evaluation at hand, the part of the matrix's diagonal that
  // the passes keep, the flesh's per-worker buffers, the contacts.
  NewtonTerms terms;
  NewtonDiagonal diagonal;
  FleshBuffers flesh_buffers;
  std::vector<Contact> contacts;
  std::vector<ContactDamper> dampers;  // with contact_damping
  // The first pass's terms but the contacts' (energy and gradient; the matrix's terms are
  // those before terms.first_contact_*): a step's later passes start where its first did,
  // the tets' rotations as it found them, and only their contacts differ.
  Eigen::VectorXd kept_gradient;
  double kept_energy = 0.0;
  // Whether the matrix's terms but the contacts' are still the kept evaluation's: not after a
  // later Newton iteration's evaluation replaced them.
  bool kept_terms_current = false;
  // The step's iterate, the line search's trial, and the prediction with its tets' rotations
  // (where a step's later passes start), kept from step to step: a study hand's state is
  // 130 kB (its tets' rotations the most), and swapped or assigned, their buffers are reused.
  StepIterate iterate, trial, rotations_found;

  Impl(const HandSimModel& m, const SimOptions& o) : model(m), options(o), pool(o.threads) {
    if (options.newton_iterations < 1)
      throw std::invalid_argument("StepSolver: at least one Newton iteration a pass");
    if (!model.kinematic_nodes)
      analyze_newton_matrix(model, memory, layout);
    else if (model.bone_count() > 0)
      throw std::logic_error("StepSolver: kinematic nodes in a model with bones");
  }

  // h^2 times the backward-Euler energy at the iterate, with `hessian` its gradient and
  // Gauss-Newton Hessian (without, as the line search needs, the energy alone). `reuse`: kKeep
  // keeps every term but the contacts'; kKept takes them from the last kKeep (or, where a later
  // evaluation has replaced its matrix's terms, evaluates and keeps them again).
  enum class Reuse { kNone, kKeep, kKept };
  double evaluate(StepIterate& it, const HandSimState& start, const std::vector<RigidPose>& targets,
                  bool hessian, Reuse reuse = Reuse::kNone) {
    terms.with_hessian = hessian;
    if (reuse == Reuse::kKept && !kept_terms_current) reuse = Reuse::kKeep;
    if (hessian) kept_terms_current = reuse != Reuse::kNone;
    if (reuse == Reuse::kKept) {
      terms.gradient = kept_gradient;
      terms.energy = kept_energy;
      terms.springs.resize(terms.first_contact_spring);
      terms.blocks.resize(terms.first_contact_block);
    } else {
      terms.clear(model.dof_count(), hessian);
      if (hessian) {
        diagonal.known = false;
        ++memory.terms_found;
      }
      add_flesh(model, it.state, terms, pool, flesh_buffers);
      add_coupling(model, it.state, terms, &layout);
      add_joints(model, it.state, terms, &layout);
      add_tracking_damping(model, it.state, start, terms);
      add_tracking(model, it.state, targets, terms);
      add_gravity(model, it.state, terms);
      add_kinetic(model, it.state, it.turned, start, terms);
      if (hessian) {
        terms.first_contact_spring = terms.springs.size();
        terms.first_contact_block = terms.blocks.size();
      }
      if (reuse == Reuse::kKeep) {
        kept_gradient = terms.gradient;
        kept_energy = terms.energy;
      }
    }
    add_contact_energies(model, it.state, contacts, terms);
    if (model.parameters.contact_damping > 0)
      add_contact_damping(model, it.state, contacts, dampers, terms);
    return terms.energy;
  }
};

StepSolver::StepSolver(const HandSimModel& model, const SimOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}
StepSolver::~StepSolver() = default;

SimStepReport StepSolver::step(const HandSimState& start, const std::vector<RigidPose>& targets,
                               HandSimState& result) {
  Impl& sim = *impl_;
  const HandSimModel& model = sim.model;
  sim.terms.scale = model.parameters.time_step * model.parameters.time_step;
  ++sim.memory.step;
  sim.memory.solves_this_step = 0;
  StepIterate& iterate = sim.iterate;
  predict(model, start, iterate);
  find_contacts(model, iterate.state, sim.contacts);
  if (model.parameters.contact_damping > 0)
    set_contact_dampers(model, start, sim.contacts, sim.dampers);

  // Newton on the step's energy, each step backtracked until the energy decreases (Armijo):
  // contacts make the energy piecewise quadratic, and a full step that runs into a surface the
  // linearisation did not see would land deep inside it. Every pass starts from the
  // prediction, and takes the flesh's terms from the first pass while they are still its first
  // evaluation's (Impl::evaluate): only contacts differ. A pass whose step stopped short
  // iterates again while no flesh touches anything (SimParameters::short_step_excess).
  SimStepReport report;
  for (int pass = 0; pass < kFrictionPasses; ++pass) {
    using Reuse = Impl::Reuse;
    if (pass > 0) iterate = sim.rotations_found;
    ScopedStepTimer evaluate_timer(report, StepTimer::kEvaluate);
    double current =
        sim.evaluate(iterate, start, targets, true, pass > 0 ? Reuse::kKept : Reuse::kKeep);
    evaluate_timer.stop();
    int iterations = sim.options.newton_iterations;
    for (int newton = 0; newton < iterations; ++newton) {
      report.residual = sim.terms.gradient.lpNorm<Eigen::Infinity>() / sim.terms.scale;
      const Eigen::VectorXd dq = model.kinematic_nodes
                                     ? solve_cube_step(model, sim.terms, report)
                                     : solve_newton_step(model, sim.terms, sim.layout, sim.diagonal,
                                                         sim.options, sim.pool, sim.memory, report);
      const double slope = sim.terms.gradient.dot(dq);
      StepIterate& trial = sim.trial;
      double length = turn_limited_length(model, dq);
      // Where the state already solves the step (CG's first residual within its tolerance, so
      // dq = 0), there is nothing to search: an energy evaluated again differs by rounding.
      const bool searched = slope < 0;
      double taken = length, reached = current;
      ScopedStepTimer search_timer(report, StepTimer::kLineSearch);
      for (int halving = 0; halving < 12 && searched; ++halving, length *= 0.5) {
        trial = iterate;
        apply_increment(model, trial.state, trial.turned, dq, length);
        taken = length;
        reached = sim.evaluate(trial, start, targets, false);
        if (reached <= current + 1e-4 * length * slope) break;
        ++report.halvings;
      }
      search_timer.stop();
      const double excess = model.parameters.short_step_excess;
      const bool more_allowed = newton + 1 == iterations &&
                                iterations < sim.options.newton_iterations + kShortStepIterations;
      if (excess > 0 && searched && more_allowed &&
          stopped_short(excess, current, reached, slope, taken) && !flesh_in_contact(sim.contacts))
        ++iterations;  // one more turn of this loop
      // The first pass's start (the prediction with its tets' rotations) is where later passes
      // start; swapped out, since `iterate` takes the trial's place next (the trial's buffer
      // then holds what is left, assigned anew before it is read).
      if (pass == 0 && newton == 0) {
        if (searched)
          std::swap(sim.rotations_found, iterate);
        else
          sim.rotations_found = iterate;
      }
      if (searched) std::swap(iterate, trial);
      report.newton_iterations += 1;
      if (newton + 1 < iterations) {
        const ScopedStepTimer timer(report, StepTimer::kEvaluate);
        current = sim.evaluate(iterate, start, targets, true);
      }
    }
    const bool entered = contacts_entered(model, iterate.state, sim.contacts);
    if (!friction_changed(model, iterate.state, sim.contacts) && !entered) break;
  }
  finish(model, start, iterate);
  report.max_penetration = update_anchors(model, sim.contacts, iterate.state);
  std::swap(result, iterate.state);
  return report;
}

bool StepSolver::flesh_touched_cube() const {
  // `curved`: inside the cube at the prediction, or carried inside by a pass.
  return std::any_of(impl_->contacts.begin(), impl_->contacts.end(),
                     [](const Contact& c) { return on_cube(c) && c.curved; });
}

}  // namespace handlab::sim
