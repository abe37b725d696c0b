// The Vulkan functions the headset display calls, from libvulkan.so.1 opened at run time (as
// the OpenXR loader is): handlab runs where Vulkan is not installed and needs it only for a
// headset. The instance and device are the OpenXR runtime's to create (XR_KHR_vulkan_enable2).
#pragma once

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <string>

namespace handlab::xr {

// A Vulkan input structure, zeroed, of its type.
template <typename T>
T vk_struct(VkStructureType type) {
  T t{};
  t.sType = type;
  return t;
}

struct VulkanFunctions {
  PFN_vkGetInstanceProcAddr get_instance_proc = nullptr;
  // The instance's.
  PFN_vkGetPhysicalDeviceQueueFamilyProperties queue_families = nullptr;
  PFN_vkGetPhysicalDeviceMemoryProperties memory_properties = nullptr;
  PFN_vkGetDeviceProcAddr get_device_proc = nullptr;
  PFN_vkDestroyInstance destroy_instance = nullptr;
  // The device's.
  PFN_vkDestroyDevice destroy_device = nullptr;
  PFN_vkGetDeviceQueue get_queue = nullptr;
  PFN_vkCreateCommandPool create_command_pool = nullptr;
  PFN_vkDestroyCommandPool destroy_command_pool = nullptr;
  PFN_vkAllocateCommandBuffers allocate_command_buffers = nullptr;
  PFN_vkBeginCommandBuffer begin_command_buffer = nullptr;
  PFN_vkEndCommandBuffer end_command_buffer = nullptr;
  PFN_vkResetCommandBuffer reset_command_buffer = nullptr;
  PFN_vkCmdPipelineBarrier pipeline_barrier = nullptr;
  PFN_vkCmdCopyBufferToImage copy_buffer_to_image = nullptr;
  PFN_vkCmdCopyImageToBuffer copy_image_to_buffer = nullptr;
  PFN_vkQueueSubmit queue_submit = nullptr;
  PFN_vkCreateFence create_fence = nullptr;
  PFN_vkDestroyFence destroy_fence = nullptr;
  PFN_vkWaitForFences wait_for_fences = nullptr;
  PFN_vkResetFences reset_fences = nullptr;
  PFN_vkCreateBuffer create_buffer = nullptr;
  PFN_vkDestroyBuffer destroy_buffer = nullptr;
  PFN_vkGetBufferMemoryRequirements buffer_requirements = nullptr;
  PFN_vkAllocateMemory allocate_memory = nullptr;
  PFN_vkFreeMemory free_memory = nullptr;
  PFN_vkBindBufferMemory bind_buffer_memory = nullptr;
  PFN_vkMapMemory map_memory = nullptr;
  PFN_vkDeviceWaitIdle device_wait_idle = nullptr;

  // libvulkan.so.1 opened and vkGetInstanceProcAddr read; "" or why not.
  std::string open_library();
  // The functions of `instance`, then of `device`; false where one is missing.
  bool load_instance(VkInstance instance);
  bool load_device(VkDevice device);
};

}  // namespace handlab::xr
