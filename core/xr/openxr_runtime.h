// What OpenXR runtime this machine has and what it offers a study: its name and version, the
// headset (the system) it drives, whether it tracks hands (XR_EXT_hand_tracking) and which
// graphics it takes. Asked of the runtime the loader finds (XR_RUNTIME_JSON, else the active
// runtime of /etc/xdg/openxr/1/active_runtime.json and the like).
#pragma once

#include <string>
#include <vector>

namespace handlab::xr {

struct OpenXrRuntimeInfo {
  bool found = false;  // a runtime answered and an instance was made
  std::string error;   // why not (the loader missing, XR_ERROR_RUNTIME_UNAVAILABLE, ...)
  std::string runtime_name, runtime_version;
  std::vector<std::string> extensions;                     // every instance extension it offers
  bool hand_tracking_extension = false;                    // XR_EXT_hand_tracking
  bool vulkan2 = false, opengl = false, headless = false;  // graphics it takes
  // The head-mounted display; where none is connected, system_error says why.
  bool system_found = false;
  std::string system_error, system_name;
  unsigned vendor_id = 0;
  bool system_tracks_hands = false;  // XrSystemHandTrackingPropertiesEXT
  bool orientation_tracking = false, position_tracking = false;
};

// Asks the runtime, making and destroying one instance named "handlab".
OpenXrRuntimeInfo probe_openxr_runtime();

// What a found runtime offers, a line each: the runtime, the headset, hand tracking, graphics.
std::string runtime_description(const OpenXrRuntimeInfo& info);

}  // namespace handlab::xr
