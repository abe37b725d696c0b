// Contact substeps of the cube alone (core/sim/cube_substeps.h): the cube among flesh points
// that follow their step's path; with no flesh near, the cube model's own substeps; in the
// scripted pinch, the hand's step left as it is.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/sim/contact_substeps.h"
#include "core/sim/cube_substeps.h"
#include "core/sim/free_cube.h"
#include "core/sim/hand_simulator.h"
#include "core/sim/sim_parameter_names.h"
#include "core/sim/step_solver.h"
#include "core/task/grasp_closing.h"
#include "core/task/pinch_scene.h"
#include "core/task/pinch_script.h"

namespace handlab::sim {
namespace cube_substeps_test {

constexpr double kStudyStep = 1.0 / 120;

SimParameters cube_substepped(int substeps, double window) {
  SimParameters p;
  set_sim_parameter(p, "contact_time_step", kStudyStep / substeps);
  set_sim_parameter(p, "contact_substep_window", window);
  set_sim_parameter(p, "contact_substeps_cube", 1);
  return p;
}

TEST(CubeSubsteps, OnByDefaultInsteadOfTheWholeHands) {
  EXPECT_TRUE(CubeSubsteps::enabled(SimParameters{})) << "the default";
  SimParameters p = cube_substepped(4, 0.1);
  EXPECT_TRUE(CubeSubsteps::enabled(p));
  EXPECT_FALSE(ContactSubsteps::enabled(p));
  set_sim_parameter(p, "contact_substeps_cube", 0);
  EXPECT_FALSE(CubeSubsteps::enabled(p));
  EXPECT_TRUE(ContactSubsteps::enabled(p));
  EXPECT_FALSE(CubeSubsteps::enabled(cube_substepped(1, 0.1)));
}

// A falling cube with the hand far away: the cube model's own steps at the substep.
TEST(CubeSubsteps, WithNoFleshNearTheCubeModelsSubsteps) {
  const SimParameters p = cube_substepped(4, 0.1);
  const PinchScene scene = make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, p);
  HandSimState start = scene.start();
  start.cube_pose.position.y() += 0.002;
  start.cube_velocity.linear = Eigen::Vector3d(0.01, -0.1, 0);
  start.cube_velocity.angular = Eigen::Vector3d(0, 0, 3);
  HandSimState result = start;
  CubeSubsteps(scene.model).step(start, result);

  SimParameters quarter = p;
  quarter.time_step = kStudyStep / 4;
  const HandSimModel cube_model = make_cube_sim_model(quarter);
  StepSolver solver(cube_model, single_threaded());
  HandSimState expected =
                   initial_state(cube_model, {}, Eigen::Isometry3d::Identity(), start.cube_pose),
               next;
  expected.time = start.time;
  expected.cube_velocity = start.cube_velocity;
  for (int i = 0; i < 4; ++i) {
    solver.step(expected, {}, next);
    expected = next;
  }
  EXPECT_LT((result.cube_pose.position - expected.cube_pose.position).norm(), 1e-12);
  EXPECT_LT(result.cube_pose.rotation.angularDistance(expected.cube_pose.rotation), 1e-12);
  EXPECT_LT((result.cube_velocity.linear - expected.cube_velocity.linear).norm(), 1e-9);
  EXPECT_EQ(result.corner_floor.size(), expected.corner_floor.size());
  EXPECT_EQ(result.node_position, start.node_position) << "the flesh is the hand step's";
}

// A point of flesh moving into the cube as a kinematic node: it lands where its velocity
// carries it, however hard the cube pushes back, and the cube is pushed away; a model with
// bones cannot hold such nodes.
TEST(CubeSubsteps, KinematicNodesGoWhereTheirVelocitiesCarryThem) {
  HandSimModel model = make_cube_sim_model(cube_substepped(4, 0.1));
  model.rest = {Eigen::Vector3d::Zero()};
  model.node_mass = {0.0};
  model.surface_nodes = {0};
  model.kinematic_nodes = true;
  RigidPose cube;
  cube.position = Eigen::Vector3d(0, 0.005, 0);
  HandSimState state = initial_state(model, {}, Eigen::Isometry3d::Identity(), cube);
  state.node_position[0] = Eigen::Vector3d(-0.0045, 0.005, 0.001);  // 0.5 mm inside the -x face
  state.node_velocity[0] = Eigen::Vector3d(0.1, 0, 0);
  StepSolver solver(model, single_threaded());
  HandSimState next;
  solver.step(state, {}, next);
  const double h = model.parameters.time_step;
  EXPECT_EQ(next.node_position[0], state.node_position[0] + h * state.node_velocity[0]);
  EXPECT_GT(next.cube_pose.position.x(), 1e-5);
  EXPECT_GT(next.cube_velocity.linear.x(), 0.0);

  HandSimModel with_bones = make_pinch_scene(0.01).model;
  with_bones.kinematic_nodes = true;
  EXPECT_THROW(StepSolver(with_bones, single_threaded()), std::logic_error);
}

// A face of flesh pushing the light cube along the floor at 5 cm/s, its path set step by step:
// the cube goes along at the face's speed, upright, with the face's points on it.
TEST(CubeSubsteps, AFacePushesTheCubeAlongAtItsSpeed) {
  const mesh::TetMesh tet{{Eigen::Vector3d(0, 0.001, -0.004), Eigen::Vector3d(0, 0.001, 0.004),
                           Eigen::Vector3d(0, 0.009, 0), Eigen::Vector3d(-0.03, 0.005, 0)},
                          {{0, 1, 2, 3}}};
  const HandSimModel model = make_soft_body_sim_model(tet, cube_substepped(4, 0.1));
  RigidPose cube;
  cube.position = Eigen::Vector3d(0.0051, 0.005, 0);  // its -x face 0.1 mm off the flesh's
  HandSimState state = initial_state(model, {}, Eigen::Isometry3d::Identity(), cube);
  CubeSubsteps substeps(model);
  const double speed = 0.05, h = model.parameters.time_step;
  for (int step = 0; step < 24; ++step) {
    HandSimState next = state;
    for (Eigen::Vector3d& x : next.node_position) x.x() += speed * h;
    next.time += h;
    substeps.step(state, next);
    state = next;
  }
  EXPECT_NEAR(state.cube_velocity.linear.x(), speed, 0.2 * speed);
  EXPECT_LT(state.cube_pose.rotation.angularDistance(Eigen::Quaterniond::Identity()), 0.05);
  EXPECT_NEAR(state.cube_pose.position.y(), 0.005, 2e-4);
  EXPECT_NEAR(state.cube_pose.position.x(), 0.0051 + 24 * speed * h, 1e-3);
  ASSERT_EQ(state.corner_floor.size(), 4u);
  ASSERT_FALSE(state.sample_cube.empty()) << "the face's centre on the cube";
  for (const ContactAnchor& a : state.sample_cube) {
    std::array<int, 3> nodes = model.skin_samples[std::size_t(a.point)].nodes;
    std::sort(nodes.begin(), nodes.end());
    EXPECT_EQ(nodes, (std::array<int, 3>{0, 1, 2})) << "sample " << a.point;
  }
}

// The scripted functional pinch: the same to the bit until flesh first touches the cube; in
// that step the flesh is where the hand's step put it and the cube is not.
TEST(CubeSubsteps, TheHandsStepIsLeftAsItIs) {
  auto run = [](const SimParameters& parameters, std::vector<HandSimState>& states) {
    const PinchScene scene = make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, parameters,
                                              PinchPosture::kFunctional);
    run_pinch(scene.model, scene.skeleton, scene.script, SimOptions{}, scene.script.close_end,
              [&](const HandSimState& s) { states.push_back(s); });
  };
  std::vector<HandSimState> plain, fine;
  run(cube_substepped(1, 0.0), plain);
  run(cube_substepped(4, 0.1), fine);
  std::size_t first = 0;
  while (first < plain.size() && plain[first].node_cube.empty() && plain[first].sample_cube.empty())
    ++first;
  ASSERT_LT(first + 13, plain.size()) << "the pads reach the cube before the closing ends";
  for (std::size_t i = 0; i < first; ++i) {
    ASSERT_EQ(fine[i].node_position, plain[i].node_position) << "step " << i;
    ASSERT_EQ(fine[i].cube_pose.position, plain[i].cube_pose.position) << "step " << i;
  }
  EXPECT_EQ(fine[first].node_position, plain[first].node_position);
  EXPECT_NE(fine[first].cube_pose.position, plain[first].cube_pose.position);
  EXPECT_NE(fine[first + 1].node_position, plain[first + 1].node_position);
}

// With cube_substeps_on_floor the cube is substepped past the window wherever the step's flesh
// touches it and it moves on the floor. Each state of the functional pinch with the thumb
// 200 ms first (which rattles the light cube on the floor) is stepped once by a simulator
// whose window is shut, with and without the rule: where a step begins no contact, its cube
// differs exactly where the rule applies. Stepping from each state, not comparing two runs,
// keeps the test off the run's path, which a build's rounding changes (in the sanitizer build
// the rattling cube leaves the floor, and the rule never applies).
TEST(CubeSubsteps, OnTheFloorPastTheWindowWhereFleshMovesTheCube) {
  SimParameters windowed = cube_substepped(4, 0.05);
  set_sim_parameter(windowed, "cube_substeps_on_floor", 0);
  SimParameters on_floor = windowed;
  set_sim_parameter(on_floor, "cube_substeps_on_floor", 1);
  PinchScene scene = make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, windowed,
                                      PinchPosture::kFunctional);
  GraspClosing thumb_first;
  thumb_first.lead_s = 0.2;
  scene.script = make_grasp_script(scene.skeleton, scene.model, thumb_first, nullptr,
                                   PinchPosture::kFunctional);
  HandSimModel model_on_floor = scene.model;
  model_on_floor.parameters = on_floor;
  std::vector<HandSimState> states;
  run_pinch(scene.model, scene.skeleton, scene.script, single_threaded(), scene.script.lift_start,
            [&](const HandSimState& s) { states.push_back(s); });
  const auto touched = [](const HandSimState& s) {
    return !s.node_cube.empty() || !s.sample_cube.empty();
  };
  std::size_t first = 0;
  while (first < states.size() && !touched(states[first])) ++first;
  ASSERT_LT(first + 30, states.size()) << "the pads reach the cube before the lift";

  const double h = windowed.time_step;
  int substepped = 0, left = 0;
  for (std::size_t k = first; k < first + 30; ++k) {
    const HandSimState& start = states[k];
    const std::vector<RigidPose> targets =
        bone_targets(scene.model, scene.skeleton, scene.script.target(double(k + 2) * h));
    StepSolver solver(scene.model, single_threaded());
    HandSimState hand_step;
    solver.step(start, targets, hand_step);
    if (ContactSubsteps::began_contact(start, hand_step)) continue;  // substepped either way
    const bool rule = solver.flesh_touched_cube() && !start.corner_floor.empty() &&
                      !FreeCubeStepper::resting(start);
    HandSimState without = start, with = start;
    HandSimulator(scene.model, single_threaded()).step(without, targets);
    HandSimulator(model_on_floor, single_threaded()).step(with, targets);
    EXPECT_EQ(with.node_position, without.node_position) << "the hand's step, state " << k;
    if (rule) {
      ++substepped;
      EXPECT_NE(with.cube_pose.position, without.cube_pose.position) << "state " << k;
    } else {
      ++left;
      EXPECT_EQ(with.cube_pose.position, without.cube_pose.position) << "state " << k;
    }
  }
  EXPECT_GT(substepped, 0) << "the thumb moves the cube on the floor";
  EXPECT_GT(left, 0) << "states the rule leaves alone";
}

}  // namespace cube_substeps_test
}  // namespace handlab::sim
