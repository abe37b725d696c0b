// The soft-hand simulator behind the trials' world interface (core/task/soft_hand_world.h):
// driven by the scripted pinch-and-lift's intermediate hands, frame by frame as a trial
// drives it, the hand lifts the cube by contact alone, reports thumb and index on it while it
// holds it, and lets it go when it opens.
#include <gtest/gtest.h>

#include "core/task/pinch_scene.h"
#include "core/task/cube_task.h"
#include "core/task/soft_hand_world.h"

namespace handlab::task {
namespace {

TEST(SoftHandWorld, PinchesLiftsAndReleasesTheCubeByContact) {
  const sim::PinchScene scene = sim::make_pinch_scene(0.06);
  const sim::PinchScript& script = scene.script;
  SoftHandWorld world(scene.model, scene.skeleton, script.cube_centre);
  EXPECT_TRUE(world.bones().empty());
  world.step(nullptr, 0.01);  // no hand yet: nothing moves
  EXPECT_EQ(world.state(), nullptr);
  EXPECT_EQ(world.cube().position, script.cube_centre);

  const double dt = 1.0 / 90;  // a tracker's rate, not the simulator's step
  bool touched_early = false, pinched_in_hold = true;
  double highest = 0.0;
  for (double t = dt; t <= script.end; t += dt) {
    const hand::HandPose target = script.target(t);
    world.step(&target, dt);
    ASSERT_EQ(world.bones().size(), scene.skeleton.bones.size());
    if (t < script.shape_end) touched_early |= world.thumb_contact() || world.index_contact();
    if (t > script.lift_end && t < script.hold_end) {
      pinched_in_hold &= world.thumb_contact() && world.index_contact();
      highest = std::max(highest, world.cube().position.y() - script.cube_centre.y());
    }
  }
  EXPECT_FALSE(touched_early) << "the hand opened 5 cm above the cube";
  EXPECT_TRUE(pinched_in_hold) << "thumb and index on the cube throughout the hold";
  EXPECT_GT(highest, 0.08) << "m: lifted by contact";
  EXPECT_FALSE(world.thumb_contact() || world.index_contact()) << "opened at the end";
  EXPECT_LT(world.cube().position.y(), script.cube_centre.y() + 0.01) << "fell back down";
  // The simulator ran in its own steps: the time the world reached is the frames' time.
  EXPECT_NEAR(world.state()->time, script.end, scene.model.parameters.time_step);
}

}  // namespace
}  // namespace handlab::task
