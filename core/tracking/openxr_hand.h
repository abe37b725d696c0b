// A hand as OpenXR's hand tracking gives it (XR_EXT_hand_tracking: 26 joints, each a pose
// and a radius) and the tracked hand the rest of handlab reads, both ways. No OpenXR header is
// needed: the joints are in XrHandJointEXT's order and its conventions, in metres, in the
// tracker's space (docs/tracking.md, "OpenXR hands").
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/tracking/tracked_frame.h"

namespace handlab::tracking {

// XrHandJointEXT: the palm and the wrist, then the thumb's metacarpal, proximal, distal and tip,
// then for index, middle, ring and little the metacarpal, proximal, intermediate, distal, tip.
inline constexpr int kOpenXrPalm = 0;
inline constexpr int kOpenXrWrist = 1;
inline constexpr int kOpenXrJointCount = 26;

// The first joint of digit d (0 thumb .. 4 little): its metacarpal joint.
constexpr int openxr_digit_base(int digit) {
  return digit == 0 ? 2 : 1 + 5 * digit;
}

// One joint as xrLocateHandJointsEXT gives it. Its orientation: +Z along the bone it starts,
// away from the tip; +Y out of the back of the hand (the nail's side); +X = Y x Z.
struct OpenXrJoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  double radius = 0.0;  // m; 0 where not known
  bool position_valid = false, orientation_valid = false;
};

struct OpenXrHand {
  Side side = Side::kRight;
  std::array<OpenXrJoint, kOpenXrJointCount> joints{};
};

// The tracked hand of these joints: the digits' joints from the joints' positions (the
// thumb's carp and mcp both at its metacarpal joint, as the Leap's zero-length thumb
// metacarpal has them), the palm's centre, normal and direction from the palm joint's pose,
// the grab and pinch strengths from the joints (grab_strength, pinch_strength below).
// nullopt when a position or the palm's orientation is not valid.
std::optional<TrackedHand> tracked_hand_from_openxr(const OpenXrHand& hand, std::int32_t id);

// The same hand as a runtime would give it: positions from the tracked joints, each joint
// turned along its bone with +Y towards the back of the hand. A Leap thumb's metacarpal joint
// is its mcp. Radii are not known (0).
OpenXrHand openxr_hand_from_tracked(const TrackedHand& hand);

// The Leap service's grab and pinch strengths (0 to 1), which OpenXR does not give, from the
// joints: grab, the four fingers' bends at mcp, pip and dip (the angles between successive
// bones) summed and averaged over the fingers, 0 at 87° and 1 at 142°; pinch, the thumb's tip
// to the index's, 1 at 23 mm and 0 at 63 mm. Both ends fitted to the service's own values in
// data/leap's five recordings (1,661 hands; mean absolute difference 0.021 and 0.002).
double grab_strength(const TrackedHand& hand);
double pinch_strength(const TrackedHand& hand);

}  // namespace handlab::tracking
