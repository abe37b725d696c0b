// A recording's tracker jitter (core/task/tracker_jitter.h): what a moving average leaves of a
// pose sequence, laid back on a pose in time.
#include "core/task/tracker_jitter.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/hand/simulated_hand.h"

namespace handlab::sim::tracker_jitter_test {
namespace {

// A slow drift plus an alternating +-0.5 mm (and +-0.01 rad on every angle) at 120 Hz: the
// moving average over 0.1 s takes the drift and leaves the alternation.
TEST(TrackerJitter, KeepsWhatIsFasterThanTheWindow) {
  const hand::Skeleton skeleton = hand::build_simulated_hand(hand::HandShape{});
  std::vector<double> times;
  std::vector<hand::HandPose> poses;
  for (int k = 0; k < 240; ++k) {
    const double t = k / 120.0, sign = k % 2 == 0 ? 1.0 : -1.0;
    hand::HandPose p = hand::HandPose::rest(skeleton);
    p.root_position = Eigen::Vector3d(0.02 * t + 0.0005 * sign, 0, 0);
    p.angles.array() += 0.1 * t + 0.01 * sign;
    times.push_back(t);
    poses.push_back(p);
  }
  const PoseJitter j = pose_jitter(times, poses, 0.1);
  // The first and last 0.05 s (6 frames each), where the window is one-sided, left out.
  ASSERT_EQ(j.times.size(), 228u);
  EXPECT_EQ(j.times.front(), 0.0);
  // Away from the ends, where the window is whole: the alternation, less what of it the
  // average of 12 or 13 frames keeps (at most a sixth).
  for (std::size_t k = 20; k < 220; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR(j.root[k].x(), 0.0005 * sign, 0.0005 / 5) << k;
    EXPECT_NEAR(j.angles[k](0), 0.01 * sign, 0.01 / 5) << k;
  }
  EXPECT_NEAR(j.root_rms(), 0.0005 / std::sqrt(3.0), 0.0001);
  // Laid on a pose: the offsets of the frame at that time, scaled, the recording looped.
  hand::HandPose pose = hand::HandPose::rest(skeleton);
  j.apply(100 / 120.0 + 1e-9, 2.0, pose);
  EXPECT_DOUBLE_EQ(pose.root_position.x(), 2 * j.root[100].x());
  hand::HandPose looped = hand::HandPose::rest(skeleton);
  j.apply(j.duration() + 100 / 120.0 + 1e-9, 2.0, looped);
  EXPECT_NEAR(looped.root_position.x(), pose.root_position.x(), 1e-12);
  EXPECT_THROW(pose_jitter({0.0}, {pose}), std::invalid_argument);
}

}  // namespace
}  // namespace handlab::sim::tracker_jitter_test
