#include "studies/participant/own_hand.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/hand/tracked_hand.h"
#include "core/tracking/hand_fitting.h"
#include "studies/participant/own_hand_posture.h"
#include "studies/participant/pinch_ik.h"

namespace handlab::studies {
namespace {

constexpr OwnHandPosture kPosture{};  // the model's (own_hand_posture.h)

// Palm down, fingers along the A-B line (+x), rolled 60 degrees towards the thumb so that
// thumb and index oppose across that line: the posture the simulator's pinch script holds
// both cubes in (core/sim/pinch_script.cpp).
Eigen::Matrix3d pinch_rotation(double roll, double pitch) {
  Eigen::Matrix3d palm_down;
  palm_down.col(0) = Eigen::Vector3d(0, 0, -1);  // radial
  palm_down.col(1) = Eigen::Vector3d(1, 0, 0);   // distal
  palm_down.col(2) = Eigen::Vector3d(0, -1, 0);  // palmar
  return Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
         Eigen::AngleAxisd(-roll, Eigen::Vector3d::UnitX()).toRotationMatrix() * palm_down;
}

}  // namespace

OwnHand::OwnHand(double hand_length)
    : skeleton_(hand::build_tracked_hand(hand::HandShape::with_length(hand_length))) {
  pad_ = build(false, pinch_rotation(kPosture.pad_roll, 0.0));
  tip_ = build(true, pinch_rotation(kPosture.tip_roll, kPosture.tip_pitch));
}

OwnHand::Table OwnHand::build(bool tip, const Eigen::Matrix3d& rotation) const {
  // Pad pinch: the pads on the palmar surface of the distal bones' middles, and points 12 mm
  // deeper, aimed along the grasp axis so that the pads face each other. Tip pinch: the
  // fingertips, and points on the bones' bases, aimed from above so that the distal
  // phalanges come down on the object at `tip_tilt` from the vertical.
  const int thumb = skeleton_.bone_index("thumb_distal");
  const int index = skeleton_.bone_index("index_distal");
  auto contact = [&](int bone) {
    const hand::Bone& b = skeleton_.bones[std::size_t(bone)];
    return tip ? Eigen::Vector3d(0, b.length, 0)
               : Eigen::Vector3d(0, kPosture.pad_along * b.length, b.radius);
  };
  auto aiming = [&](int bone) {
    const hand::Bone& b = skeleton_.bones[std::size_t(bone)];
    return tip ? Eigen::Vector3d(0, kPosture.tip_aim_along * b.length, 0)
               : Eigen::Vector3d(0, kPosture.pad_along * b.length, b.radius - kPosture.aim_depth);
  };
  hand::HandPose pose = hand::HandPose::rest(skeleton_);
  pose.root_rotation = rotation;
  auto curl_others = [&](double gap) {
    const double c =
        kPosture.others_curl_closed + (kPosture.others_curl_open - kPosture.others_curl_closed) *
                                          std::clamp(gap / kPosture.others_open_at, 0.0, 1.0);
    for (std::size_t k = 0; k < skeleton_.dofs.size(); ++k) {
      const hand::Dof& dof = skeleton_.dofs[k];
      const bool other = dof.name.rfind("middle", 0) == 0 || dof.name.rfind("ring", 0) == 0 ||
                         dof.name.rfind("pinky", 0) == 0;
      if (other && dof.name.find("flexion") != std::string::npos)
        pose.angles(Eigen::Index(k)) = c * dof.upper;
    }
  };
  curl_others(0.0);
  auto point = [&](const hand::BoneFrames& f, int bone, const Eigen::Vector3d& local) {
    return hand::bone_point(f, bone, local);
  };
  // The grasp axis: across the A-B line (z), the thumb on its own side.
  const hand::BoneFrames start = hand::forward_kinematics(skeleton_, pose);
  const Eigen::Vector3d axis(
      0, 0,
      (point(start, thumb, contact(thumb)) - point(start, index, contact(index))).z() > 0 ? 1.0
                                                                                          : -1.0);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const double thumb_reach = kPosture.tip_reach * skeleton_.bones[std::size_t(thumb)].length;
  const double index_reach = kPosture.tip_reach * skeleton_.bones[std::size_t(index)].length;
  Table table{rotation, {}};
  for (double gap = kPosture.widest_gap; gap > -1e-9; gap -= kPosture.gap_step) {
    curl_others(gap);
    const hand::BoneFrames frames = hand::forward_kinematics(skeleton_, pose);
    const Eigen::Vector3d centre =
        0.5 * (point(frames, thumb, contact(thumb)) + point(frames, index, contact(index)));
    const double half = 0.5 * gap;
    const Eigen::Vector3d thumb_at = centre + axis * half, index_at = centre - axis * half;
    const Eigen::Vector3d thumb_aim =
        tip ? Eigen::Vector3d(thumb_at + thumb_reach * (std::sin(kPosture.tip_tilt) * axis +
                                                        std::cos(kPosture.tip_tilt) * up))
            : Eigen::Vector3d(centre + axis * (half + kPosture.aim_depth));
    const Eigen::Vector3d index_aim =
        tip ? Eigen::Vector3d(index_at + index_reach * (-std::sin(kPosture.tip_tilt) * axis +
                                                        std::cos(kPosture.tip_tilt) * up))
            : Eigen::Vector3d(centre - axis * (half + kPosture.aim_depth));
    const std::vector<PointGoal> goals = {{thumb, contact(thumb), thumb_at, 1.0},
                                          {index, contact(index), index_at, 1.0},
                                          {thumb, aiming(thumb), thumb_aim, kPosture.aim_weight},
                                          {index, aiming(index), index_aim, kPosture.aim_weight}};
    solve_pinch_ik(skeleton_, pose, goals, kPosture.ik);
    const hand::BoneFrames solved = hand::forward_kinematics(skeleton_, pose);
    const Eigen::Vector3d t = point(solved, thumb, contact(thumb));
    const Eigen::Vector3d i = point(solved, index, contact(index));
    table.postures.push_back({(t - i).norm(), pose.angles, 0.5 * (t + i) - pose.root_position});
  }
  std::sort(table.postures.begin(), table.postures.end(),
            [](const Posture& a, const Posture& b) { return a.aperture < b.aperture; });
  // Keep a strictly increasing aperture (an unreachable gap repeats its neighbour's).
  std::vector<Posture> kept;
  for (const Posture& p : table.postures)
    if (kept.empty() || p.aperture > kept.back().aperture + kPosture.keep_step) kept.push_back(p);
  table.postures = std::move(kept);
  return table;
}

hand::HandPose OwnHand::pose(Pinch pinch, const Eigen::Vector3d& grip, double aperture) const {
  const Table& t = pinch == Pinch::kPad ? pad_ : tip_;
  const std::vector<Posture>& postures = t.postures;
  aperture = std::clamp(aperture, postures.front().aperture, postures.back().aperture);
  std::size_t k = 0;
  while (k + 2 < postures.size() && postures[k + 1].aperture < aperture) ++k;
  const Posture& a = postures[k];
  const Posture& b = postures[std::min(k + 1, postures.size() - 1)];
  const double w =
      b.aperture > a.aperture ? (aperture - a.aperture) / (b.aperture - a.aperture) : 0;
  hand::HandPose pose = hand::HandPose::rest(skeleton_);
  pose.root_rotation = t.rotation;
  pose.angles = a.angles + w * (b.angles - a.angles);
  pose.root_position = grip - (a.grip_from_root + w * (b.grip_from_root - a.grip_from_root));
  return pose;
}

hand::HandPose OwnHand::open_palm(const Eigen::Vector3d& palm) const {
  hand::HandPose pose = hand::HandPose::rest(skeleton_);
  pose.root_rotation.col(0) = -Eigen::Vector3d::UnitX();
  pose.root_rotation.col(1) = -Eigen::Vector3d::UnitZ();
  pose.root_rotation.col(2) = -Eigen::Vector3d::UnitY();
  const hand::LeapJoints j = hand::to_leap_joints(skeleton_, pose);
  pose.root_position = palm - j.palm_position;
  return pose;
}

tracking::TrackedFrame OwnHand::frame(const hand::HandPose& pose, double time, long id,
                                      const std::vector<Eigen::Vector3d>& jitter) const {
  hand::LeapJoints joints = hand::to_leap_joints(skeleton_, pose);
  if (jitter.size() >= 25)
    for (std::size_t d = 0; d < 5; ++d)
      for (std::size_t k = 0; k < 5; ++k) joints.joints[d][k] += jitter[d * 5 + k];
  tracking::TrackedFrame f;
  f.timestamp = time;
  f.id = id;
  f.hands.push_back(tracking::tracked_hand(joints, tracking::Side::kRight));
  return f;
}

}  // namespace handlab::studies
