// Both hands' trackers of an OpenXR session (XR_EXT_hand_tracking), and their joints located
// at a time as the tracked hands the rest of handlab reads (core/tracking/openxr_hand.h). A
// session with no graphics (the hand source) and the headset display's own both use them.
#pragma once

#include <string>
#include <vector>

#include "core/tracking/tracked_frame.h"
#include "core/xr/openxr_functions.h"

namespace handlab::xr {

class HandTrackers {
 public:
  // "" or why the session tracks no hands.
  std::string create(const OpenXrFunctions& xr, XrSession session);
  void destroy(const OpenXrFunctions& xr);
  bool created() const { return trackers_[0] != XR_NULL_HANDLE; }
  // The hands tracked at `time`, their joints in `space` (left: id 1, right: id 2).
  std::vector<tracking::TrackedHand> locate(const OpenXrFunctions& xr, XrSpace space,
                                            XrTime time) const;

 private:
  XrHandTrackerEXT trackers_[2] = {XR_NULL_HANDLE, XR_NULL_HANDLE};  // left, right
};

}  // namespace handlab::xr
