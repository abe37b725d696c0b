// Contact substeps (core/sim/contact_substeps.h): a step in which flesh begins to touch the
// cube is the model's own step at the shorter time step, taken several times with the targets
// moved along the way; the steps before any contact are the same to the bit; the window after
// a contact began counts its steps.
#include <gtest/gtest.h>

#include "core/sim/contact_substeps.h"
#include "core/sim/sim_parameter_names.h"
#include "core/sim/step_solver.h"
#include "core/task/pinch_scene.h"

namespace handlab::sim {
namespace contact_substeps_test {

constexpr double kStudyStep = 1.0 / 120;

// The whole hand's substeps (not the cube's alone, the default's).
SimParameters substepped(int substeps, double window) {
  SimParameters p;
  set_sim_parameter(p, "contact_time_step", kStudyStep / substeps);
  set_sim_parameter(p, "contact_substep_window", window);
  set_sim_parameter(p, "contact_substeps_cube", 0);
  return p;
}

std::vector<ContactAnchor> anchors(std::initializer_list<int> points) {
  std::vector<ContactAnchor> out;
  for (int p : points) out.push_back({p, Eigen::Vector3d::Zero()});
  return out;
}

TEST(ContactSubsteps, BeganWhereAFleshPointTouchesThatDidNotBefore) {
  HandSimState before, after;
  before.node_cube = anchors({3, 8});
  before.sample_cube = anchors({2});
  after = before;
  EXPECT_FALSE(ContactSubsteps::began_contact(before, after));
  after.node_cube = anchors({8});
  EXPECT_FALSE(ContactSubsteps::began_contact(before, after)) << "one let go";
  after.node_cube = anchors({3, 5, 8});
  EXPECT_TRUE(ContactSubsteps::began_contact(before, after)) << "node 5";
  after = before;
  after.sample_cube = anchors({2, 9});
  EXPECT_TRUE(ContactSubsteps::began_contact(before, after)) << "sample 9";
  EXPECT_FALSE(ContactSubsteps::enabled(SimParameters{})) << "the default's are the cube's";
  EXPECT_FALSE(ContactSubsteps::enabled(substepped(1, 0.1)));
  EXPECT_TRUE(ContactSubsteps::enabled(substepped(4, 0.0)));
}

// The substeps of a step are the model at a quarter of the step, its targets a quarter, a half
// and three quarters of the way from the step before's and then the step's own (to rounding).
TEST(ContactSubsteps, AStepIsTheModelsAtTheShorterStepWithTheTargetsMovedAlong) {
  const PinchScene scene =
      make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, substepped(4, 0.0));
  const HandSimModel& model = scene.model;
  const HandSimState start = scene.start();
  const double t = scene.script.approach_end;  // the fingers closing
  const std::vector<RigidPose> from = bone_targets(model, scene.skeleton, scene.script.target(t)),
                               to = bone_targets(model, scene.skeleton,
                                                 scene.script.target(t + 0.05));
  ContactSubsteps substeps(model, SimOptions{});
  HandSimState result;
  const SimStepReport report = substeps.step(start, from, to, result);

  HandSimModel quarter = model;
  quarter.parameters.time_step = kStudyStep / 4;
  StepSolver solver(quarter, SimOptions{});
  HandSimState expected = start, next;
  int newton = 0;
  for (int i = 1; i <= 4; ++i) {
    std::vector<RigidPose> targets(to.size());
    for (std::size_t b = 0; b < to.size(); ++b) {
      targets[b].position = (1 - i / 4.0) * from[b].position + i / 4.0 * to[b].position;
      targets[b].rotation = from[b].rotation.slerp(i / 4.0, to[b].rotation);
    }
    newton += solver.step(expected, targets, next).newton_iterations;
    expected = next;
  }
  // Equal to rounding: the targets are interpolated in another translation unit, which the
  // compiler may vectorise otherwise (the sanitizers' build differed in the last bits).
  ASSERT_EQ(result.node_position.size(), expected.node_position.size());
  for (std::size_t n = 0; n < expected.node_position.size(); ++n)
    ASSERT_LT((result.node_position[n] - expected.node_position[n]).norm(), 1e-9) << "node " << n;
  for (std::size_t b = 0; b < expected.bone_pose.size(); ++b)
    ASSERT_LT((result.bone_pose[b].position - expected.bone_pose[b].position).norm(), 1e-9)
        << "bone " << b;
  EXPECT_NEAR(result.time, start.time + kStudyStep, 1e-12);
  EXPECT_EQ(report.newton_iterations, newton);
}

// The window after a contact began: contact_substep_window in steps, opened anew by each step
// that began a contact, counted down by each step taken in it.
TEST(ContactSubsteps, TheWindowCountsItsSteps) {
  SimParameters p = substepped(2, 0.05);  // 6 steps of 1/120 s
  const HandSimModel model = make_cube_sim_model(p);
  ContactSubsteps substeps(model, SimOptions{});
  EXPECT_EQ(substeps.substeps(), 2);
  EXPECT_FALSE(substeps.in_window());
  substeps.open_window();
  for (int i = 0; i < 6; ++i) {
    EXPECT_TRUE(substeps.in_window()) << "step " << i << " of the window";
    substeps.count_down();
    if (i == 2) substeps.open_window();  // a contact began in the window's third step
  }
  for (int i = 0; i < 3; ++i) substeps.count_down();
  EXPECT_FALSE(substeps.in_window());
  substeps.count_down();
  EXPECT_FALSE(substeps.in_window());
}

// The scripted functional pinch with contact substeps: the same to the bit until flesh first
// touches the cube; that step is taken again in four substeps (its Newton iterations the coarse
// step's and four more), as without a window, and the window's 12 steps (0.1 s) each in four,
// some of which without a window are not.
TEST(ContactSubsteps, OnlyWhereFleshBeginsToTouchTheCube) {
  auto run = [](const SimParameters& parameters, std::vector<HandSimState>& states) {
    const PinchScene scene = make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, parameters,
                                              PinchPosture::kFunctional);
    return run_pinch(scene.model, scene.skeleton, scene.script, SimOptions{},
                     scene.script.close_end, [&](const HandSimState& s) { states.push_back(s); });
  };
  std::vector<HandSimState> plain, fine, no_window;
  run(substepped(1, 0.0), plain);
  const PinchReport report = run(substepped(4, 0.1), fine);
  const PinchReport without_window = run(substepped(4, 0.0), no_window);
  std::size_t first = 0;
  while (first < plain.size() && plain[first].node_cube.empty() && plain[first].sample_cube.empty())
    ++first;
  ASSERT_LT(first + 13, plain.size()) << "the pads reach the cube before the closing ends";
  for (std::size_t i = 0; i < first; ++i)
    ASSERT_EQ(fine[i].node_position, plain[i].node_position) << "step " << i;
  EXPECT_NE(fine[first].node_position, plain[first].node_position);
  EXPECT_GE(report.newton_iterations[first], 5);
  EXPECT_EQ(no_window[first].node_position, fine[first].node_position) << "the first touch";
  int plain_without_window = 0;
  for (std::size_t i = first + 1; i <= first + 12; ++i) {
    EXPECT_GE(report.newton_iterations[i], 4) << "step " << i - first << " of the window";
    plain_without_window += without_window.newton_iterations[i] < 4;
  }
  EXPECT_GT(plain_without_window, 0) << "steps that only the window takes in substeps";
}

}  // namespace contact_substeps_test
}  // namespace handlab::sim
