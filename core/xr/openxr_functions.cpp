#include "core/xr/openxr_functions.h"

namespace handlab::xr {

bool OpenXrFunctions::load(const OpenXrLoader& l, XrInstance i) {
  bool all = true;
  auto get = [&](auto& f, const char* name, bool core) {
    f = l.get<std::remove_reference_t<decltype(f)>>(i, name);
    if (core && !f) all = false;
  };
  get(instance_properties, "xrGetInstanceProperties", true);
  get(destroy_instance, "xrDestroyInstance", true);
  get(get_system, "xrGetSystem", true);
  get(create_session, "xrCreateSession", true);
  get(destroy_session, "xrDestroySession", true);
  get(begin_session, "xrBeginSession", true);
  get(end_session, "xrEndSession", true);
  get(request_exit, "xrRequestExitSession", true);
  get(poll_event, "xrPollEvent", true);
  get(wait_frame, "xrWaitFrame", true);
  get(begin_frame, "xrBeginFrame", true);
  get(end_frame, "xrEndFrame", true);
  get(locate_views, "xrLocateViews", true);
  get(configuration_views, "xrEnumerateViewConfigurationViews", true);
  get(create_space, "xrCreateReferenceSpace", true);
  get(destroy_space, "xrDestroySpace", true);
  get(swapchain_formats, "xrEnumerateSwapchainFormats", true);
  get(create_swapchain, "xrCreateSwapchain", true);
  get(destroy_swapchain, "xrDestroySwapchain", true);
  get(swapchain_images, "xrEnumerateSwapchainImages", true);
  get(acquire_image, "xrAcquireSwapchainImage", true);
  get(wait_image, "xrWaitSwapchainImage", true);
  get(release_image, "xrReleaseSwapchainImage", true);
  get(create_hand_tracker, "xrCreateHandTrackerEXT", false);
  get(destroy_hand_tracker, "xrDestroyHandTrackerEXT", false);
  get(locate_hand_joints, "xrLocateHandJointsEXT", false);
  get(convert_time, "xrConvertTimespecTimeToTimeKHR", false);
  get(vulkan_requirements, "xrGetVulkanGraphicsRequirements2KHR", false);
  get(create_vulkan_instance, "xrCreateVulkanInstanceKHR", false);
  get(vulkan_device, "xrGetVulkanGraphicsDevice2KHR", false);
  get(create_vulkan_device, "xrCreateVulkanDeviceKHR", false);
  return all;
}

}  // namespace handlab::xr
