// The OpenXR functions handlab's sessions call, read once from the loader for an instance: the
// core ones a session needs, then those of the extensions it enabled (null where not enabled).
#pragma once

#include <time.h>

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include "core/xr/openxr_loader.h"

#define XR_USE_TIMESPEC
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr_platform.h>

namespace handlab::xr {

struct OpenXrFunctions {
  PFN_xrGetInstanceProperties instance_properties = nullptr;
  PFN_xrDestroyInstance destroy_instance = nullptr;
  PFN_xrGetSystem get_system = nullptr;
  PFN_xrCreateSession create_session = nullptr;
  PFN_xrDestroySession destroy_session = nullptr;
  PFN_xrBeginSession begin_session = nullptr;
  PFN_xrEndSession end_session = nullptr;
  PFN_xrRequestExitSession request_exit = nullptr;
  PFN_xrPollEvent poll_event = nullptr;
  PFN_xrWaitFrame wait_frame = nullptr;
  PFN_xrBeginFrame begin_frame = nullptr;
  PFN_xrEndFrame end_frame = nullptr;
  PFN_xrLocateViews locate_views = nullptr;
  PFN_xrEnumerateViewConfigurationViews configuration_views = nullptr;
  PFN_xrCreateReferenceSpace create_space = nullptr;
  PFN_xrDestroySpace destroy_space = nullptr;
  PFN_xrEnumerateSwapchainFormats swapchain_formats = nullptr;
  PFN_xrCreateSwapchain create_swapchain = nullptr;
  PFN_xrDestroySwapchain destroy_swapchain = nullptr;
  PFN_xrEnumerateSwapchainImages swapchain_images = nullptr;
  PFN_xrAcquireSwapchainImage acquire_image = nullptr;
  PFN_xrWaitSwapchainImage wait_image = nullptr;
  PFN_xrReleaseSwapchainImage release_image = nullptr;
  // XR_EXT_hand_tracking
  PFN_xrCreateHandTrackerEXT create_hand_tracker = nullptr;
  PFN_xrDestroyHandTrackerEXT destroy_hand_tracker = nullptr;
  PFN_xrLocateHandJointsEXT locate_hand_joints = nullptr;
  // XR_KHR_convert_timespec_time
  PFN_xrConvertTimespecTimeToTimeKHR convert_time = nullptr;
  // XR_KHR_vulkan_enable2
  PFN_xrGetVulkanGraphicsRequirements2KHR vulkan_requirements = nullptr;
  PFN_xrCreateVulkanInstanceKHR create_vulkan_instance = nullptr;
  PFN_xrGetVulkanGraphicsDevice2KHR vulkan_device = nullptr;
  PFN_xrCreateVulkanDeviceKHR create_vulkan_device = nullptr;

  // False where a core function is missing.
  bool load(const OpenXrLoader& loader, XrInstance instance);
};

}  // namespace handlab::xr
