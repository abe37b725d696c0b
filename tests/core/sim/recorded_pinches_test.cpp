// Real closings on the soft hand (core/task/recorded_pinches.h): a closing is found where the
// pads' aperture falls past the cube's side, the cube is placed between the pads at that
// moment, and a closing that cannot take the cube is told apart. The poses are the scripted
// pinch's closing sampled as a recording would be, so every aperture is known.
#include <cmath>

#include <gtest/gtest.h>

#include "core/task/finger_pads.h"
#include "core/task/pinch_scene.h"
#include "core/task/recorded_pinches.h"

namespace handlab::sim::recorded_pinches_test {
namespace {

struct Sampled {
  std::vector<double> times;
  std::vector<hand::HandPose> poses;
};

// The scripted 1 cm pinch from its approach's end to the hold's, at 100 frames a second,
// moved 20 cm aside and turned 40 degrees about the vertical, as a recording is anywhere.
Sampled sampled_closing(const PinchScene& scene) {
  Sampled s;
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(40 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (double t = scene.script.approach_end; t < scene.script.lift_start; t += 0.01) {
    hand::HandPose pose = scene.script.target(t);
    const Eigen::Vector3d aside(0.2, 0.1, 0.0);
    pose.root_position = turn * pose.root_position + aside;
    pose.root_rotation = turn * pose.root_rotation;
    s.times.push_back(100 + t);
    s.poses.push_back(pose);
  }
  return s;
}

TEST(RecordedPinches, AClosingPastTheSideIsFoundAndItsCubePlacedBetweenThePads) {
  const PinchScene scene = make_pinch_scene(0.01);
  const Sampled rec = sampled_closing(scene);
  const std::vector<double> apertures = pad_apertures(scene.skeleton, scene.model, rec.poses);
  const std::vector<RecordedClosing> closings =
      find_recorded_closings(scene.skeleton, scene.model, rec.times, rec.poses);
  ASSERT_EQ(closings.size(), 1u);
  const RecordedClosing& c = closings[0];
  EXPECT_TRUE(c.takes_cube);
  EXPECT_EQ(c.widest, apertures.front());
  EXPECT_EQ(c.narrowest, *std::min_element(apertures.begin(), apertures.end()));
  // The moment: the last frame whose aperture is at least the side.
  EXPECT_GE(apertures[std::size_t(c.moment_frame)], 0.01);
  EXPECT_LT(apertures[std::size_t(c.moment_frame) + 1], 0.01);
  EXPECT_GT(c.closing_speed, 0.0);
  // Half a second before the moment, or the recording's start.
  EXPECT_NEAR(c.moment - rec.times[std::size_t(c.first_frame)],
              std::min(0.5, c.moment - rec.times.front()), 0.011);

  const PinchScript script =
      make_recorded_pinch_script(scene.skeleton, scene.model, rec.times, rec.poses, c);
  const double moment = script.approach_end + c.moment - rec.times[std::size_t(c.first_frame)] +
                        0.001;  // within the moment's frame
  const hand::HandPose at = script.target(moment);
  const hand::BoneFrames f = hand::forward_kinematics(scene.skeleton, at);
  const auto pad = [&](int bone) -> Eigen::Vector3d {
    const Eigen::Vector3d local = finger_pad(scene.skeleton, scene.model, bone);
    return f.origin[std::size_t(bone)] + f.rotation[std::size_t(bone)] * local;
  };
  const Eigen::Vector3d thumb = pad(script.thumb_bone), index = pad(script.index_bone);
  EXPECT_LT((0.5 * (thumb + index) - script.cube_centre).norm(), 1e-9);
  EXPECT_NEAR((thumb - index).normalized().z(), 1.0, 1e-9) << "level, along the cube's z";
  EXPECT_NEAR((thumb - index).norm(), apertures[std::size_t(c.moment_frame)], 1e-9);
  // After the recording the fingers stay closed and the lift carries them up.
  const hand::HandPose lifted = script.target(script.lift_end + 0.1);
  EXPECT_EQ(lifted.angles, script.recorded_poses.back().angles);
  EXPECT_NEAR(lifted.root_position.y() - script.recorded_poses.back().root_position.y(),
              script.lift_height, 1e-12);
}

TEST(RecordedPinches, AClosingThatNeverOpensToTheSideIsNotRun) {
  const PinchScene small = make_pinch_scene(0.01), large = make_pinch_scene(0.06);
  const Sampled rec = sampled_closing(small);  // opens to about 4 cm
  const std::vector<RecordedClosing> closings =
      find_recorded_closings(large.skeleton, large.model, rec.times, rec.poses);
  ASSERT_EQ(closings.size(), 1u);
  EXPECT_FALSE(closings[0].takes_cube);
  EXPECT_LT(closings[0].widest, 0.06);
  EXPECT_THROW(
      make_recorded_pinch_script(large.skeleton, large.model, rec.times, rec.poses, closings[0]),
      std::invalid_argument);
}

}  // namespace
}  // namespace handlab::sim::recorded_pinches_test
