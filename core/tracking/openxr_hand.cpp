#include "core/tracking/openxr_hand.h"

#include <algorithm>
#include <cmath>

namespace handlab::tracking {

namespace {

// The tracked joint (digit, k: 0 carp .. 4 tip) at OpenXR joint j of that digit (0 its
// metacarpal joint .. its tip): a finger's five map one to one; the thumb has four, its
// metacarpal joint standing for the Leap's carp and mcp at once.
int tracked_index(int digit, int j) {
  return digit == 0 ? j + 1 : j;
}
int openxr_joint_count(int digit) {
  return digit == 0 ? 4 : 5;
}

// A frame whose +Z is `backward` (unit) and whose +Y is `lateral` x +Z: for a finger's bone
// the side of its nail, whatever its bend, as the bone turns about the lateral axis. A bone
// along the lateral axis (a thumb may lie so) takes `back` (the back of the hand) for +Y.
Eigen::Quaterniond bone_frame(const Eigen::Vector3d& backward, const Eigen::Vector3d& lateral,
                              const Eigen::Vector3d& back) {
  Eigen::Vector3d y = lateral.cross(backward);
  if (y.norm() < 1e-6) y = back;
  y = (y - y.dot(backward) * backward).normalized();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(backward);
  r.col(1) = y;
  r.col(2) = backward;
  return Eigen::Quaterniond(r).normalized();
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

std::optional<TrackedHand> tracked_hand_from_openxr(const OpenXrHand& xr, std::int32_t id) {
  for (const OpenXrJoint& j : xr.joints)
    if (!j.position_valid || !j.position.allFinite()) return std::nullopt;
  const OpenXrJoint& palm = xr.joints[kOpenXrPalm];
  if (!palm.orientation_valid) return std::nullopt;
  TrackedHand h;
  h.id = id;
  h.side = xr.side;
  for (int d = 0; d < 5; ++d)
    for (int j = 0; j < openxr_joint_count(d); ++j)
      h.joints[std::size_t(d)][std::size_t(tracked_index(d, j))] =
          xr.joints[std::size_t(openxr_digit_base(d) + j)].position;
  h.joints[0][0] = h.joints[0][1];
  const Eigen::Matrix3d r = palm.orientation.normalized().toRotationMatrix();
  h.palm_position = palm.position;
  h.palm_normal = -r.col(1);
  h.direction = -r.col(2);
  h.wrist = xr.joints[kOpenXrWrist].position;
  h.grab_strength = grab_strength(h);
  h.pinch_strength = pinch_strength(h);
  return h;
}

OpenXrHand openxr_hand_from_tracked(const TrackedHand& h) {
  OpenXrHand xr;
  xr.side = h.side;
  const Eigen::Matrix3d palm = palm_frame(h);  // +x = direction x normal
  const Eigen::Quaterniond palm_rotation = bone_frame(-palm.col(1), palm.col(0), -palm.col(2));
  xr.joints[kOpenXrPalm] = {h.palm_position, palm_rotation, 0.0, true, true};
  xr.joints[kOpenXrWrist] = {h.wrist, palm_rotation, 0.0, true, true};
  for (int d = 0; d < 5; ++d) {
    const int count = openxr_joint_count(d);
    for (int j = 0; j < count; ++j) {
      const auto& digit = h.joints[std::size_t(d)];
      const Eigen::Vector3d& p = digit[std::size_t(tracked_index(d, j))];
      // The bone a joint starts; the tip takes its distal phalanx's.
      const int from = j + 1 < count ? j : j - 1;
      const Eigen::Vector3d along = digit[std::size_t(tracked_index(d, from + 1))] -
                                    digit[std::size_t(tracked_index(d, from))];
      const Eigen::Vector3d backward = along.norm() > 1e-9 ? Eigen::Vector3d(-along.normalized())
                                                           : Eigen::Vector3d(-palm.col(1));
      xr.joints[std::size_t(openxr_digit_base(d) + j)] = {
          p, bone_frame(backward, palm.col(0), -palm.col(2)), 0.0, true, true};
    }
  }
  return xr;
}

double grab_strength(const TrackedHand& h) {
  constexpr double kOpen = 87.0 * M_PI / 180.0, kFist = 142.0 * M_PI / 180.0;
  double bend = 0.0;
  for (int d = 1; d < 5; ++d) {
    const auto& j = h.joints[std::size_t(d)];
    for (int k = 0; k + 2 < 5; ++k) bend += angle_between(j[k + 1] - j[k], j[k + 2] - j[k + 1]);
  }
  return std::clamp((bend / 4.0 - kOpen) / (kFist - kOpen), 0.0, 1.0);
}

double pinch_strength(const TrackedHand& h) {
  constexpr double kTouch = 0.023, kOpen = 0.063;
  return std::clamp((kOpen - thumb_index_distance(h)) / (kOpen - kTouch), 0.0, 1.0);
}

}  // namespace handlab::tracking
