#include "core/sim/free_cube.h"

#include <utility>

namespace handlab::sim {
namespace {

SimParameters substepped(SimParameters p) {
  p.time_step /= FreeCubeStepper::kSubsteps;
  return p;
}

// A corner that lands within a substep lies deep at the prediction, where the stiffened floor's
// force (k d + k3 d^2) is far from the linear one Newton iteration solves exactly: from there
// one iteration left it pressed in and the landing threw the cube back up (a light cube spun at
// 150 rad/s gained 7.9 times its energy). Three solve the substep (docs/simulator.md, "Solver");
// six unknowns, a few microseconds each.
SimOptions free_cube_options() {
  SimOptions o = single_threaded();
  o.newton_iterations = FreeCubeStepper::kNewtonIterations;
  return o;
}

}  // namespace

FreeCubeStepper::FreeCubeStepper(const SimParameters& parameters)
    : model_(make_cube_sim_model(substepped(parameters))), solver_(model_, free_cube_options()) {}

bool FreeCubeStepper::resting(const HandSimState& state) {
  // Flat on its four corners and slower than this, it rests: a step with the hand keeps it
  // there. On fewer corners a full step could launch it off the floor.
  constexpr double kResting = 1e-3, kRestingSpin = 0.1;  // m/s, rad/s
  return state.corner_floor.size() == 4 && state.cube_velocity.linear.norm() < kResting &&
         state.cube_velocity.angular.norm() < kRestingSpin;
}

bool FreeCubeStepper::applies(const HandSimState& start, bool flesh_touching) {
  return !flesh_touching && !resting(start);
}

void FreeCubeStepper::step(const HandSimState& start, HandSimState& result) {
  HandSimState cube = initial_state(model_, {}, Eigen::Isometry3d::Identity(), start.cube_pose);
  cube.time = start.time;
  cube.cube_velocity = start.cube_velocity;
  cube.corner_floor = start.corner_floor;
  HandSimState next;
  for (int i = 0; i < kSubsteps; ++i) {
    solver_.step(cube, {}, next);
    std::swap(cube, next);
  }
  result.cube_pose = cube.cube_pose;
  result.cube_velocity = cube.cube_velocity;
  result.corner_floor = cube.corner_floor;
}

}  // namespace handlab::sim
