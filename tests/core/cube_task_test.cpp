// The pick-and-place state machine and the grasp-proxy world it runs on.
#include <gtest/gtest.h>

#include "core/hand/simulated_hand.h"
#include "core/task/cube_task.h"
#include "core/task/grasp_proxy.h"

namespace handlab::task {
namespace {

TaskSettings settings() {
  TaskSettings s;
  s.layout.cube_size = 0.01;
  s.timeout = 20.0;
  return s;
}

struct Script {
  CubeTask& task;
  double t = 0.0;
  // Steps at 100 Hz for `seconds` with the cube at p and the given contacts.
  void hold(double seconds, Eigen::Vector3d p, bool touching, Eigen::Vector3d v = {0, 0, 0}) {
    for (int k = 0; k < int(seconds * 100 + 0.5); ++k) {
      t += 0.01;
      TaskObservation o;
      o.time = t;
      o.cube_position = p;
      o.cube_velocity = v;
      o.thumb_contact = o.index_contact = touching;
      task.update(o);
    }
  }
};

TEST(CubeTask, PickMoveAndPlaceInB) {
  CubeTask task(settings());
  const SceneLayout& l = task.settings().layout;
  task.start(0.0);
  Script s{task};
  const Eigen::Vector3d on_a = l.zone_a + Eigen::Vector3d(0, 0.005, 0);
  const Eigen::Vector3d on_b = l.zone_b + Eigen::Vector3d(0.02, 0.005, 0);
  s.hold(1.0, on_a, true);  // touched on the floor: not yet a grasp
  EXPECT_EQ(task.phase(), TaskPhase::kStarted);
  s.hold(1.0, on_a + Eigen::Vector3d(0, 0.05, 0), true);
  EXPECT_EQ(task.phase(), TaskPhase::kGrasped);
  s.hold(1.0, on_b, true);  // put down, still held
  EXPECT_EQ(task.phase(), TaskPhase::kGrasped);
  s.hold(0.3, on_b, false);
  EXPECT_EQ(task.phase(), TaskPhase::kReleased);
  s.hold(0.3, on_b, false);
  EXPECT_EQ(task.phase(), TaskPhase::kDone);
  EXPECT_EQ(task.grasps(), 1);
  EXPECT_EQ(task.drops(), 0);
  // Released at 3.01, resting from the next step: put down at 3.02, not 0.5 s later.
  EXPECT_NEAR(task.completion_time(), 3.02, 1e-9);
  ASSERT_EQ(task.events().size(), 4u);
  EXPECT_EQ(task.events()[1].kind, "grasp");
  EXPECT_EQ(task.events().back().kind, "done");
}

TEST(CubeTask, DropOutsideBWaitsForAnotherGraspAndMovingCubesDoNotCount) {
  CubeTask task(settings());
  const SceneLayout& l = task.settings().layout;
  task.start(0.0);
  Script s{task};
  const Eigen::Vector3d lifted = l.zone_a + Eigen::Vector3d(0, 0.05, 0);
  const Eigen::Vector3d floor_between(0.0, 0.005, 0.0);
  s.hold(0.2, lifted, true);
  s.hold(0.2, lifted, false);
  s.hold(0.4, floor_between, false);
  EXPECT_EQ(task.phase(), TaskPhase::kReleased) << "not yet seen to stay there";
  s.hold(0.2, floor_between, false);
  EXPECT_EQ(task.phase(), TaskPhase::kStarted);
  EXPECT_EQ(task.drops(), 1);
  ASSERT_EQ(task.events().back().kind, "drop");
  EXPECT_NEAR(task.events().back().time, 0.41, 1e-9) << "when it came to rest";
  s.hold(0.2, lifted, true);
  EXPECT_EQ(task.grasps(), 2);
  s.hold(0.2, l.zone_b + Eigen::Vector3d(0, 0.05, 0), false);
  // Sliding through B is not resting in it.
  s.hold(1.0, l.zone_b + Eigen::Vector3d(0, 0.005, 0), false, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(task.phase(), TaskPhase::kReleased);
  s.hold(0.6, l.zone_b + Eigen::Vector3d(0, 0.005, 0), false);
  EXPECT_EQ(task.phase(), TaskPhase::kDone);
}

// A released cube that pauses out of B for a moment (the top of a roll, the edge of a
// tumble) and then slides on into B and stays there was put in B: no drop, and no new grasp
// needed (before, the pause counted as a drop and the trial waited for a grasp of a cube
// lying in B).
TEST(CubeTask, APauseOnTheWayIntoBIsNotADrop) {
  CubeTask task(settings());
  const SceneLayout& l = task.settings().layout;
  task.start(0.0);
  Script s{task};
  s.hold(0.2, l.zone_a + Eigen::Vector3d(0, 0.05, 0), true);
  s.hold(0.1, l.zone_b + Eigen::Vector3d(-0.07, 0.05, 0), false);  // let go short of B
  s.hold(0.05, l.zone_b + Eigen::Vector3d(-0.06, 0.005, 0), false);  // paused out of B
  s.hold(0.1, l.zone_b + Eigen::Vector3d(-0.04, 0.005, 0), false, Eigen::Vector3d(0.2, 0, 0));
  EXPECT_EQ(task.drops(), 0);
  s.hold(0.6, l.zone_b + Eigen::Vector3d(-0.03, 0.005, 0), false);  // stays in B
  EXPECT_EQ(task.phase(), TaskPhase::kDone);
  EXPECT_EQ(task.drops(), 0);
  EXPECT_EQ(task.grasps(), 1);
}

TEST(CubeTask, TimeoutFails) {
  CubeTask task(settings());
  task.start(0.0);
  Script s{task};
  s.hold(25.0, task.settings().layout.zone_a + Eigen::Vector3d(0, 0.005, 0), false);
  EXPECT_EQ(task.phase(), TaskPhase::kFailed);
  EXPECT_DOUBLE_EQ(task.completion_time(), 20.0);
  EXPECT_EQ(task.events().back().kind, "timeout");
  EXPECT_EQ(task.events().size(), 2u);
}

TEST(GraspProxy, FreeCubeFallsAtGAndRestsOnTheFloor) {
  const hand::Skeleton s = hand::build_simulated_hand(hand::HandShape::with_length(0.214));
  GraspProxySettings gs;
  gs.cube_size = 0.06;
  GraspProxyWorld world(s, gs, Eigen::Vector3d(0, 0.5, 0));
  const double dt = 1e-3;
  for (int k = 0; k < 200; ++k) world.step(nullptr, dt);
  // Semi-implicit Euler: y = y0 - g dt^2 n(n+1)/2.
  EXPECT_NEAR(world.cube().position.y(), 0.5 - 9.81 * dt * dt * 200 * 201 / 2, 1e-12);
  for (int k = 0; k < 2000; ++k) world.step(nullptr, dt);
  EXPECT_DOUBLE_EQ(world.cube().position.y(), 0.03);
  EXPECT_TRUE(world.cube().velocity.isZero());
}

}  // namespace
}  // namespace handlab::task
