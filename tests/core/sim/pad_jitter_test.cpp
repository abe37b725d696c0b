// A tracker's jitter at the pads (core/task/pad_jitter.h): each pad's displacement and the
// pads' against each other, along the line between them and across it.
#include "core/task/pad_jitter.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "core/hand/simulated_hand.h"

namespace handlab::sim::pad_jitter_test {
namespace {

constexpr double kStep = 1.0 / 120;

struct Hand {
  hand::Skeleton skeleton = hand::build_simulated_hand(hand::HandShape{});
  hand::HandPose pinch = hand::HandPose::rest(skeleton);
  PinchPads pads;
  Hand() {
    pads.thumb_bone = skeleton.bone_index("thumb3");
    pads.index_bone = skeleton.bone_index("index3");
    pads.thumb_pad =
        Eigen::Vector3d(0, 0.5 * skeleton.bones[std::size_t(pads.thumb_bone)].length, 0);
    pads.index_pad =
        Eigen::Vector3d(0, 0.5 * skeleton.bones[std::size_t(pads.index_bone)].length, 0);
  }
};

// A jitter of one frame a step, alternating between +offset and -offset.
PoseJitter alternating(const Hand& h, const Eigen::Vector3d& root, int dof, double angle) {
  PoseJitter j;
  for (int k = 0; k < 24; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    j.times.push_back(k * kStep);
    j.root.push_back(sign * root);
    j.turn.push_back(Eigen::Vector3d::Zero());
    Eigen::VectorXd a = Eigen::VectorXd::Zero(h.pinch.angles.size());
    if (dof >= 0) a(dof) = sign * angle;
    j.angles.push_back(a);
  }
  return j;
}

// The wrist shifted moves both pads alike: each by the shift, neither against the other.
TEST(PadJitter, AShiftOfTheWholeHandMovesNeitherPadAgainstTheOther) {
  const Hand h;
  const PoseJitter j = alternating(h, Eigen::Vector3d(0.0003, -0.0004, 0), -1, 0.0);
  const PadJitter p = pad_jitter(h.skeleton, h.pinch, h.pads, j, 2.0, kStep);
  EXPECT_EQ(p.scale, 2.0);
  EXPECT_NEAR(p.thumb_rms, 0.001, 1e-12);  // 2 x 0.5 mm
  EXPECT_NEAR(p.index_rms, 0.001, 1e-12);
  EXPECT_NEAR(p.along_rms, 0.0, 1e-12);
  EXPECT_NEAR(p.across_rms, 0.0, 1e-12);
  EXPECT_NEAR(p.relative_speed_max, 0.0, 1e-9);
}

// The index's DIP turned alone moves the index pad alone, round the joint: the pads' relative
// displacement is the index pad's, and it changes by twice it each step.
TEST(PadJitter, OneFingersJointMovesThatPadAgainstTheOther) {
  const Hand h;
  const int dip = h.skeleton.dof_index("index_dip_flexion");
  const PoseJitter j = alternating(h, Eigen::Vector3d::Zero(), dip, 0.01);
  const PadJitter p = pad_jitter(h.skeleton, h.pinch, h.pads, j, 1.0, kStep);
  EXPECT_NEAR(p.thumb_rms, 0.0, 1e-12);
  EXPECT_GT(p.index_rms, 0.0);
  EXPECT_NEAR(std::hypot(p.along_rms, p.across_rms), p.index_rms, 1e-12);
  // Along the line between the pads: the pad's move turned +-0.01 rad, seen on that line.
  const auto index_pad = [&](double turn) {
    hand::HandPose pose = h.pinch;
    pose.angles(dip) += turn;
    const hand::BoneFrames f = hand::forward_kinematics(h.skeleton, pose);
    return hand::bone_point(f, h.pads.index_bone, h.pads.index_pad);
  };
  const hand::BoneFrames still = hand::forward_kinematics(h.skeleton, h.pinch);
  const Eigen::Vector3d axis =
      (index_pad(0.0) - hand::bone_point(still, h.pads.thumb_bone, h.pads.thumb_pad)).normalized();
  const double plus = (index_pad(0.01) - index_pad(0.0)).dot(axis),
               minus = (index_pad(-0.01) - index_pad(0.0)).dot(axis);
  EXPECT_NEAR(p.along_rms, std::sqrt((12 * plus * plus + 11 * minus * minus) / 23), 1e-12)
      << "23 steps over the recording's 23 step-long frames, 12 of them turned +0.01 rad";
  // A pad half the distal bone out, turned 0.01 rad: about 0.01 x that radius.
  const double radius = h.pads.index_pad.y();
  EXPECT_NEAR(p.index_rms, 0.01 * radius, 0.01 * radius * 1e-3);
  EXPECT_NEAR(p.relative_speed_rms, 2 * p.index_rms / kStep, 1e-3 * p.relative_speed_rms);
  EXPECT_NEAR(p.relative_speed_max, p.relative_speed_rms, 1e-9);
  // Half the jitter, half of every figure (to the first order of the turn).
  const PadJitter half = pad_jitter(h.skeleton, h.pinch, h.pads, j, 0.5, kStep);
  EXPECT_NEAR(half.index_rms, 0.5 * p.index_rms, 1e-4 * p.index_rms);
  const PadJitter none = pad_jitter(h.skeleton, h.pinch, h.pads, j, 0.0, kStep);
  EXPECT_EQ(none.index_rms, 0.0);
  EXPECT_EQ(none.relative_speed_max, 0.0);
}

// The whole hand turned about an axis across the line between the pads turns that line: the
// pads move against each other across it, by the turn times their distance, and not along it.
TEST(PadJitter, AHandTurnedMovesThePadsAcrossTheirLine) {
  const Hand h;
  const hand::BoneFrames frames = hand::forward_kinematics(h.skeleton, h.pinch);
  const Eigen::Vector3d line = hand::bone_point(frames, h.pads.index_bone, h.pads.index_pad) -
                               hand::bone_point(frames, h.pads.thumb_bone, h.pads.thumb_pad);
  const double angle = 0.002;  // rad
  PoseJitter j = alternating(h, Eigen::Vector3d::Zero(), -1, 0.0);
  for (std::size_t k = 0; k < j.turn.size(); ++k)
    j.turn[k] = (k % 2 == 0 ? angle : -angle) * line.unitOrthogonal();
  const PadJitter p = pad_jitter(h.skeleton, h.pinch, h.pads, j, 1.0, kStep);
  EXPECT_NEAR(p.across_rms, angle * line.norm(), 1e-3 * angle * line.norm());
  EXPECT_LT(p.along_rms, 1e-2 * p.across_rms);
}

TEST(PadJitter, RefusesWhatItCannotMeasure) {
  Hand h;
  const PoseJitter j = alternating(h, Eigen::Vector3d(0.001, 0, 0), -1, 0.0);
  EXPECT_THROW(pad_jitter(h.skeleton, h.pinch, h.pads, j, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(pad_jitter(h.skeleton, h.pinch, h.pads, j, 1.0, 1.0), std::invalid_argument);
  h.pads.index_bone = 99;
  EXPECT_THROW(pad_jitter(h.skeleton, h.pinch, h.pads, j, 1.0, kStep), std::invalid_argument);
}

}  // namespace
}  // namespace handlab::sim::pad_jitter_test
