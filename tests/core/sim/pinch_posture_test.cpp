// The scripted pinch placed in a functional posture (core/task/pinch_posture.h): the pads on
// the same goals, the wrist turned so that the thumb's and index's joints keep off their
// limits, where the pads' inverse kinematics with the wrist's turn fixed leaves the light
// cube's thumb at two of its limits and the index's knuckles on the cube's top.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/task/pinch_scene.h"

namespace handlab::sim {
namespace {

// The posture's DOFs of `pose` within `margin` (rad) of a limit.
int joints_at_limits(const hand::Skeleton& skeleton, const hand::HandPose& pose, double margin) {
  int at = 0;
  for (const int k : posture_dofs(skeleton)) {
    const hand::Dof& dof = skeleton.dofs[std::size_t(k)];
    if (pose.angles(k) < dof.lower + margin || pose.angles(k) > dof.upper - margin) ++at;
  }
  return at;
}

TEST(PinchPosture, KeepsTheLightCubesPinchOffItsLimitsAndItsTopFree) {
  const double margin = 5 * M_PI / 180;
  const PinchScene solved = make_pinch_scene(0.01);
  EXPECT_GE(joints_at_limits(solved.skeleton, solved.script.pinch, margin), 3)
      << "the thumb's CMC flexion and rotation, the index's abduction";
  const PinchScene scene = make_pinch_scene(0.01, 1, 0.003, 0.214, {}, PinchPosture::kFunctional);
  const PinchScript& script = scene.script;
  EXPECT_EQ(script.posture, PinchPosture::kFunctional);
  EXPECT_FALSE(script.placed_by_rule);
  EXPECT_LT(script.pinch_error, 0.001) << "m: the pads on their goals";
  EXPECT_EQ(joints_at_limits(scene.skeleton, script.pinch, margin), 0);
  EXPECT_LE(joints_at_limits(scene.skeleton, script.open, margin), 1)
      << "the index's abduction, 3.4° inside, as the pads open 15 mm each";
  const PinchReport r = run_pinch(scene.model, scene.skeleton, script);
  EXPECT_TRUE(r.held);
  EXPECT_TRUE(r.released);
  EXPECT_LT(r.top_load_before_closing_n, 1.0) << "the solved posture's knuckles: 23.5 N";
}

// The heavy cube's functional pinch is placed by the pinch's rule (pinch_clearance.h), drawn
// towards the functional posture: without that draw the rule's least squares kept the index's
// PIP at its 110° limit and the pads 4.7 mm off their goals. Closed, it keeps every joint 10°
// inside its limits.
TEST(PinchPosture, TheRuleKeepsTheHeavyCubesPinchOffItsLimits) {
  const PinchScene scene = make_pinch_scene(0.06, 1, 0.003, 0.214, {}, PinchPosture::kFunctional);
  const PinchScript& script = scene.script;
  EXPECT_TRUE(script.placed_by_rule);
  EXPECT_TRUE(script.pinch_meets_rule);
  EXPECT_LT(script.placement_pad_error, 0.001) << "m";
  EXPECT_EQ(joints_at_limits(scene.skeleton, script.pinch, 10 * M_PI / 180), 0);
}

TEST(PinchPosture, IsNamedAndItsAnglesSourced) {
  EXPECT_EQ(parse_pinch_posture("functional"), PinchPosture::kFunctional);
  EXPECT_EQ(parse_pinch_posture(pinch_posture_name(PinchPosture::kSolved)), PinchPosture::kSolved);
  EXPECT_THROW(parse_pinch_posture("natural"), std::invalid_argument);
  const FunctionalPosture& posture = functional_posture();
  EXPECT_EQ(posture.angles.size(), 9u);
  for (const PostureAngle& a : posture.angles) EXPECT_FALSE(a.source.empty()) << a.dof;
}

}  // namespace
}  // namespace handlab::sim
