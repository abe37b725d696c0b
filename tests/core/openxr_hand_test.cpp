// OpenXR's 26 hand joints and the tracked hand, both ways, on the real Leap recordings.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/tracking/hand_fitting.h"
#include "core/tracking/openxr_hand.h"
#include "core/tracking/recording_io.h"

namespace handlab::tracking {
namespace {

const std::vector<std::string> kRecordings = {"confidence2", "grab", "pinch-57fps", "pinch",
                                              "wave"};

Recording recording(const std::string& name) {
  return read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/" + name + ".json.lz");
}

// A flat right hand, palm down (normal -y), fingers along -z, the index bent 90° at its mcp.
TrackedHand flat_hand_with_bent_index() {
  TrackedHand h;
  h.palm_normal = -Eigen::Vector3d::UnitY();
  h.direction = -Eigen::Vector3d::UnitZ();
  h.palm_position = Eigen::Vector3d(0, 0, -0.04);
  h.wrist = Eigen::Vector3d::Zero();
  for (int d = 0; d < 5; ++d)
    for (int k = 0; k < 5; ++k)
      h.joints[d][k] =
          Eigen::Vector3d(0.02 * (d - 2), 0, -0.02 - 0.025 * (d == 0 ? std::max(k, 1) : k));
  const Eigen::Vector3d mcp = h.joints[1][1];
  for (int k = 2; k < 5; ++k) h.joints[1][k] = mcp + Eigen::Vector3d(0, -0.025 * (k - 1), 0);
  return h;
}

TEST(OpenXrHand, JointsFollowXrHandJointExtOrder) {
  EXPECT_EQ(openxr_digit_base(0), 2);   // XR_HAND_JOINT_THUMB_METACARPAL_EXT
  EXPECT_EQ(openxr_digit_base(1), 6);   // XR_HAND_JOINT_INDEX_METACARPAL_EXT
  EXPECT_EQ(openxr_digit_base(2), 11);  // XR_HAND_JOINT_MIDDLE_METACARPAL_EXT
  EXPECT_EQ(openxr_digit_base(3), 16);  // XR_HAND_JOINT_RING_METACARPAL_EXT
  EXPECT_EQ(openxr_digit_base(4), 21);  // XR_HAND_JOINT_LITTLE_METACARPAL_EXT
  EXPECT_EQ(openxr_digit_base(4) + 4, kOpenXrJointCount - 1);  // XR_HAND_JOINT_LITTLE_TIP_EXT
}

TEST(OpenXrHand, OrientationsFollowTheExtensionsConventions) {
  const OpenXrHand xr = openxr_hand_from_tracked(flat_hand_with_bent_index());
  const Eigen::Matrix3d palm = xr.joints[kOpenXrPalm].orientation.toRotationMatrix();
  EXPECT_LT((palm.col(1) - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // +Y: the back of the hand
  EXPECT_LT((palm.col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);  // +Z: towards the wrist
  // The index's proximal phalanx points down: +Z up its bone, its nail (+Y) towards the fingers.
  const Eigen::Matrix3d proximal = xr.joints[7].orientation.toRotationMatrix();
  EXPECT_LT((proximal.col(2) - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((proximal.col(1) + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  for (const OpenXrJoint& j : xr.joints)
    EXPECT_NEAR(j.orientation.toRotationMatrix().determinant(), 1.0, 1e-12);
}

TEST(OpenXrHand, TheThumbsMetacarpalJointIsTheLeapsCarpAndMcp) {
  const Recording r = recording("pinch");
  const TrackedHand& leap = r.frames.front().hands.front();
  const OpenXrHand xr = openxr_hand_from_tracked(leap);
  EXPECT_EQ(xr.joints[2].position, leap.joints[0][1]);
  EXPECT_EQ(xr.joints[3].position, leap.joints[0][2]);
  EXPECT_EQ(xr.joints[5].position, leap.joints[0][4]);
  // The anatomical metacarpal, not a zero-length bone: 40-50 mm in these recordings.
  EXPECT_GT((xr.joints[3].position - xr.joints[2].position).norm(), 0.035);
  const auto back = tracked_hand_from_openxr(xr, leap.id);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->joints[0][0], back->joints[0][1]);
}

TEST(OpenXrHand, EveryRecordedHandComesBackAsItWent) {
  for (const std::string& name : kRecordings) {
    const Recording r = recording(name);
    for (const TrackedFrame& f : r.frames)
      for (const TrackedHand& h : f.hands) {
        const auto back = tracked_hand_from_openxr(openxr_hand_from_tracked(h), h.id);
        ASSERT_TRUE(back) << name;
        for (int d = 0; d < 5; ++d)
          for (int k = 0; k < 5; ++k) ASSERT_LT((back->joints[d][k] - h.joints[d][k]).norm(), 1e-9);
        ASSERT_LT((back->palm_position - h.palm_position).norm(), 1e-9) << name;
        ASSERT_LT((back->wrist - h.wrist).norm(), 1e-9) << name;
        // The Leap's normal and direction are orthogonal to within its float precision.
        ASSERT_LT((back->palm_normal - h.palm_normal).norm(), 1e-5) << name;
        ASSERT_LT((back->direction - h.direction).norm(), 1e-5) << name;
        ASSERT_EQ(back->side, h.side);
      }
  }
}

TEST(OpenXrHand, GrabAndPinchStrengthsAgreeWithTheLeapServices) {
  double grab = 0.0, pinch = 0.0;
  int hands = 0;
  for (const std::string& name : kRecordings)
    for (const TrackedFrame& f : recording(name).frames)
      for (const TrackedHand& h : f.hands) {
        grab += std::abs(grab_strength(h) - h.grab_strength);
        pinch += std::abs(pinch_strength(h) - h.pinch_strength);
        ++hands;
      }
  ASSERT_EQ(hands, 1661);
  EXPECT_LT(grab / hands, 0.025);
  EXPECT_LT(pinch / hands, 0.005);
  TrackedHand flat = flat_hand_with_bent_index();
  flat.joints[1] = flat.joints[2];  // every finger straight
  EXPECT_EQ(grab_strength(flat), 0.0);
}

TEST(OpenXrHand, AHandWithoutAJointsPositionIsNoHand) {
  OpenXrHand xr = openxr_hand_from_tracked(flat_hand_with_bent_index());
  ASSERT_TRUE(tracked_hand_from_openxr(xr, 1));
  xr.joints[9].position_valid = false;
  EXPECT_FALSE(tracked_hand_from_openxr(xr, 1));
  xr = openxr_hand_from_tracked(flat_hand_with_bent_index());
  xr.joints[kOpenXrPalm].orientation_valid = false;
  EXPECT_FALSE(tracked_hand_from_openxr(xr, 1));
  xr = openxr_hand_from_tracked(flat_hand_with_bent_index());
  xr.joints[4].position.x() = NAN;
  EXPECT_FALSE(tracked_hand_from_openxr(xr, 1));
}

// The mapping's error as the session sees it: the tracked skeleton fitted to the joints.
TEST(OpenXrHand, TheTrackedSkeletonFitsJointsReadThroughOpenXr) {
  Recording r = recording("pinch");
  for (TrackedFrame& f : r.frames)
    for (TrackedHand& h : f.hands) h = *tracked_hand_from_openxr(openxr_hand_from_tracked(h), h.id);
  auto fitter = TrackedHandFitter::for_recording(r.frames, Side::kRight);
  ASSERT_TRUE(fitter);
  double mean = 0.0;
  for (const TrackedFrame& f : r.frames) mean += fitter->fit(f.hands.front()).rms_residual;
  mean /= double(r.frames.size());
  EXPECT_LT(mean, 0.001);  // 0.8 mm, as the Leap's own joints
}

}  // namespace
}  // namespace handlab::tracking
