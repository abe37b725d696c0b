#include "core/xr/openxr_runtime.h"

#include <algorithm>

#include "core/xr/openxr_loader.h"

namespace handlab::xr {

namespace {

constexpr const char* kHandTracking = "XR_EXT_hand_tracking";
constexpr const char* kVulkan2 = "XR_KHR_vulkan_enable2";
constexpr const char* kOpenGl = "XR_KHR_opengl_enable";
constexpr const char* kHeadless = "XR_MND_headless";

bool offered(const std::vector<std::string>& extensions, const char* name) {
  return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
}

// The instance extensions the runtime (and its API layers) offer; false with `error` set where
// no runtime answers.
bool list_extensions(const OpenXrLoader& loader, std::vector<std::string>& out,
                     std::string& error) {
  auto enumerate = loader.get<PFN_xrEnumerateInstanceExtensionProperties>(
      XR_NULL_HANDLE, "xrEnumerateInstanceExtensionProperties");
  if (!enumerate)
    return error = "the OpenXR loader has no xrEnumerateInstanceExtensionProperties", false;
  uint32_t count = 0;
  XrResult r = enumerate(nullptr, 0, &count, nullptr);
  std::vector<XrExtensionProperties> properties(
      count, xr_struct<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
  if (XR_SUCCEEDED(r)) r = enumerate(nullptr, count, &count, properties.data());
  if (XR_FAILED(r)) return error = "no OpenXR runtime answered: " + result_name(r), false;
  for (const auto& p : properties) out.emplace_back(p.extensionName);
  return true;
}

void describe_system(const OpenXrLoader& loader, XrInstance instance, OpenXrRuntimeInfo& info) {
  auto get_system = loader.get<PFN_xrGetSystem>(instance, "xrGetSystem");
  auto get_properties = loader.get<PFN_xrGetSystemProperties>(instance, "xrGetSystemProperties");
  if (!get_system || !get_properties) {
    info.system_error = "the runtime has no xrGetSystem";
    return;
  }
  auto request = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  request.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  const XrResult r = get_system(instance, &request, &system);
  if (XR_FAILED(r)) {
    info.system_error = "no head-mounted display: " + result_name(r);
    return;
  }
  auto hands =
      xr_struct<XrSystemHandTrackingPropertiesEXT>(XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT);
  auto properties = xr_struct<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
  if (info.hand_tracking_extension) properties.next = &hands;
  if (XR_FAILED(get_properties(instance, system, &properties))) {
    info.system_error = "the runtime did not describe its headset";
    return;
  }
  info.system_found = true;
  info.system_name = properties.systemName;
  info.vendor_id = properties.vendorId;
  info.system_tracks_hands = info.hand_tracking_extension && hands.supportsHandTracking;
  info.orientation_tracking = properties.trackingProperties.orientationTracking;
  info.position_tracking = properties.trackingProperties.positionTracking;
}

std::string version_text(XrVersion v) {
  return std::to_string(XR_VERSION_MAJOR(v)) + "." + std::to_string(XR_VERSION_MINOR(v)) + "." +
         std::to_string(XR_VERSION_PATCH(v));
}

}  // namespace

OpenXrRuntimeInfo probe_openxr_runtime() {
  OpenXrRuntimeInfo info;
  const OpenXrLoader& loader = OpenXrLoader::instance();
  if (!loader.available()) return info.error = loader.error(), info;
  if (!list_extensions(loader, info.extensions, info.error)) return info;
  info.hand_tracking_extension = offered(info.extensions, kHandTracking);
  info.vulkan2 = offered(info.extensions, kVulkan2);
  info.opengl = offered(info.extensions, kOpenGl);
  info.headless = offered(info.extensions, kHeadless);

  std::vector<const char*> enabled;
  if (info.hand_tracking_extension) enabled.push_back(kHandTracking);
  XrInstance instance = XR_NULL_HANDLE;
  const XrResult r = create_instance(loader, enabled, &instance);
  if (XR_FAILED(r))
    return info.error = "the OpenXR runtime made no instance: " + result_name(r), info;

  auto properties = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  auto get_properties =
      loader.get<PFN_xrGetInstanceProperties>(instance, "xrGetInstanceProperties");
  if (get_properties && XR_SUCCEEDED(get_properties(instance, &properties))) {
    info.runtime_name = properties.runtimeName;
    info.runtime_version = version_text(properties.runtimeVersion);
  }
  info.found = true;
  describe_system(loader, instance, info);
  if (auto destroy = loader.get<PFN_xrDestroyInstance>(instance, "xrDestroyInstance"))
    destroy(instance);
  return info;
}

std::string runtime_description(const OpenXrRuntimeInfo& info) {
  const auto yes_no = [](bool b) { return std::string(b ? "yes" : "no"); };
  std::string text = "OpenXR runtime   " + info.runtime_name + " " + info.runtime_version + "\n";
  text += info.system_found ? "headset          " + info.system_name +
                                  " (orientation tracked: " + yes_no(info.orientation_tracking) +
                                  ", position tracked: " + yes_no(info.position_tracking) + ")\n"
                            : "headset          none: " + info.system_error + "\n";
  text += std::string("hand tracking    XR_EXT_hand_tracking ") +
          (info.hand_tracking_extension ? "offered" : "not offered") +
          (info.system_found ? "; the headset tracks hands: " + yes_no(info.system_tracks_hands)
                             : std::string()) +
          "\n";
  text += "graphics         Vulkan (XR_KHR_vulkan_enable2): " + yes_no(info.vulkan2) +
          ", OpenGL (XR_KHR_opengl_enable): " + yes_no(info.opengl) +
          ", none (XR_MND_headless): " + yes_no(info.headless) + "\n";
  return text;
}

}  // namespace handlab::xr
