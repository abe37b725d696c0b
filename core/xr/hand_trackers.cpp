#include "core/xr/hand_trackers.h"

#include "core/tracking/openxr_hand.h"

namespace handlab::xr {

namespace {

tracking::OpenXrHand openxr_hand(const std::vector<XrHandJointLocationEXT>& joints,
                                 tracking::Side side) {
  tracking::OpenXrHand hand;
  hand.side = side;
  for (int j = 0; j < tracking::kOpenXrJointCount; ++j) {
    const XrHandJointLocationEXT& in = joints[std::size_t(j)];
    tracking::OpenXrJoint& out = hand.joints[std::size_t(j)];
    out.position = {in.pose.position.x, in.pose.position.y, in.pose.position.z};
    out.orientation = Eigen::Quaterniond(in.pose.orientation.w, in.pose.orientation.x,
                                         in.pose.orientation.y, in.pose.orientation.z);
    out.radius = in.radius;
    out.position_valid = in.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT;
    out.orientation_valid = in.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  }
  return hand;
}

}  // namespace

std::string HandTrackers::create(const OpenXrFunctions& xr, XrSession session) {
  if (!xr.create_hand_tracker || !xr.locate_hand_joints || !xr.destroy_hand_tracker)
    return "the OpenXR runtime tracks no hands (no XR_EXT_hand_tracking)";
  for (int side = 0; side < 2; ++side) {
    auto info = xr_struct<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    info.hand = side == 0 ? XR_HAND_LEFT_EXT : XR_HAND_RIGHT_EXT;
    info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
    if (const XrResult r = xr.create_hand_tracker(session, &info, &trackers_[side]); XR_FAILED(r)) {
      destroy(xr);
      return std::string("the OpenXR runtime tracks no ") + (side == 0 ? "left" : "right") +
             " hand: " + result_name(r);
    }
  }
  return "";
}

void HandTrackers::destroy(const OpenXrFunctions& xr) {
  for (XrHandTrackerEXT& t : trackers_)
    if (t != XR_NULL_HANDLE) {
      xr.destroy_hand_tracker(t);
      t = XR_NULL_HANDLE;
    }
}

std::vector<tracking::TrackedHand> HandTrackers::locate(const OpenXrFunctions& xr, XrSpace space,
                                                        XrTime time) const {
  std::vector<tracking::TrackedHand> hands;
  for (int side = 0; side < 2; ++side) {
    std::vector<XrHandJointLocationEXT> joints(tracking::kOpenXrJointCount);
    auto locations = xr_struct<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
    locations.jointCount = std::uint32_t(joints.size());
    locations.jointLocations = joints.data();
    auto info = xr_struct<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    info.baseSpace = space;
    info.time = time;
    if (XR_FAILED(xr.locate_hand_joints(trackers_[side], &info, &locations)) || !locations.isActive)
      continue;
    const auto s = side == 0 ? tracking::Side::kLeft : tracking::Side::kRight;
    if (auto hand = tracking::tracked_hand_from_openxr(openxr_hand(joints, s), side + 1))
      hands.push_back(*hand);
  }
  return hands;
}

}  // namespace handlab::xr
