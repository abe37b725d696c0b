// A grasp's closing read back from a frame log (studies/analysis/logged_closing.h): frames
// made from the grasp map's own script for a known closing, so that the reading can be
// checked against what the map asked for.
#include "studies/analysis/logged_closing.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/task/cube_task.h"
#include "core/task/grasp_closing.h"
#include "core/task/pinch_clearance.h"
#include "core/task/pinch_scene.h"

namespace handlab::studies::logged_closing_test {
namespace {

// The script's intermediate hand at 120 Hz from the approach's end to the lift, the cube at
// rest where the script puts it: grasped from the closing's end; the thumb touching from
// `thumb_touch` (s), the index from `index_touch`.
std::vector<store::FrameRecord> frames_of(const sim::PinchScript& s, double thumb_touch,
                                          double index_touch) {
  std::vector<store::FrameRecord> frames;
  for (double t = s.approach_end; t < s.lift_start; t += 1.0 / 120) {
    const hand::HandPose pose = s.target(t);
    store::FrameRecord f;
    f.time = t;
    f.root_position = pose.root_position.cast<float>();
    f.root_rotation = Eigen::Quaterniond(pose.root_rotation).cast<float>();
    for (Eigen::Index d = 0; d < pose.angles.size(); ++d) f.angles.push_back(float(pose.angles(d)));
    f.cube_position = s.cube_centre.cast<float>();
    f.task_phase =
        std::uint8_t(t >= s.close_end ? task::TaskPhase::kGrasped : task::TaskPhase::kStarted);
    f.thumb_contact = t >= thumb_touch;
    f.index_contact = t >= index_touch;
    frames.push_back(f);
  }
  return frames;
}

TEST(LoggedClosing, ReadsBackTheClosingTheMapAskedFor) {
  const sim::PinchScene scene = sim::make_pinch_scene(0.06);
  sim::GraspClosing asked;
  sim::set_closing_factor(asked, "over_closure", 10);
  sim::set_closing_factor(asked, "tilt_pitch", 10);
  sim::set_closing_factor(asked, "offset_along", 0.2);
  sim::set_closing_factor(asked, "closing_speed", 5);
  const sim::PinchScript s = sim::make_grasp_script(scene.skeleton, scene.model, asked);
  const double middle = 0.5 * (s.approach_end + s.close_end);
  const std::vector<store::FrameRecord> frames = frames_of(s, middle, middle + 0.1);
  std::size_t grasp = 0;
  while (frames[grasp].task_phase != std::uint8_t(task::TaskPhase::kGrasped)) ++grasp;
  const LoggedClosing c = ClosingReader(scene.shape).read(frames, grasp, 0.06);
  // The inverse kinematics misses the pads' targets by pinch_error (2.8 mm here): the reading
  // is as close as the pose the script made.
  EXPECT_NEAR(c.over_closure, 0.010, s.pinch_error);
  EXPECT_NEAR(c.tilt_pitch, 10 * M_PI / 180, 3 * M_PI / 180);
  EXPECT_LT(c.tilt_yaw, 3 * M_PI / 180);
  EXPECT_NEAR(c.offset_along, 0.2, 0.05);
  EXPECT_NEAR(c.lead_s, 0.1, 1.0 / 120);
  // Over the 0.1 s before the middle of a smooth closing of mean 5 cm/s (0.5 s long) the pads
  // move at about 1.45 times it.
  EXPECT_NEAR(c.closing_speed, 0.072, 0.015);
  // The other fingers' skin in the cube, the map's pinch's own (10 mm past the faces, the
  // fingers flexed on through them), with the cube where the frames have it.
  const auto depth_at = [&](double raised) {
    sim::RigidPose cube;
    cube.position = s.cube_centre + Eigen::Vector3d(0, raised, 0);
    return -sim::skin_clearance(scene.skeleton, scene.model, s.pinch, cube, scene.model.cube_half,
                                {s.thumb_bone, s.index_bone})
                .distance;
  };
  EXPECT_NEAR(c.other_skin_depth, depth_at(0.0), 1e-5);
  std::vector<store::FrameRecord> higher = frames;
  for (store::FrameRecord& f : higher) f.cube_position.y() += 0.05f;
  EXPECT_NEAR(ClosingReader(scene.shape).read(higher, grasp, 0.06).other_skin_depth, depth_at(0.05),
              1e-5);
  EXPECT_NE(depth_at(0.05), depth_at(0.0));
}

TEST(LoggedClosing, SpreadsAreRsType7Quantiles) {
  std::vector<LoggedClosing> closings(5);
  for (int i = 0; i < 5; ++i) closings[std::size_t(i)].over_closure = 0.001 * (i + 1);
  closings[2].lead_s = std::nan("");
  const LoggedFactor& over = logged_factors()[0];
  const FactorSpread s = factor_spread(closings, over);
  EXPECT_EQ(s.n, 5);
  // R: quantile(1:5, c(0.1, 0.5, 0.9)) is 1.4, 3, 4.6.
  EXPECT_NEAR(s.p10, 1.4, 1e-12);
  EXPECT_NEAR(s.median, 3.0, 1e-12);
  EXPECT_NEAR(s.p90, 4.6, 1e-12);
  EXPECT_EQ(factor_spread(closings, logged_factors()[4]).n, 4) << "NaN left out";
}

}  // namespace
}  // namespace handlab::studies::logged_closing_test
