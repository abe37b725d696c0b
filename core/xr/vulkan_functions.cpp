#include "core/xr/vulkan_functions.h"

#include <dlfcn.h>

namespace handlab::xr {

std::string VulkanFunctions::open_library() {
  void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library) return "no Vulkan loader (libvulkan.so.1, Debian's libvulkan1)";
  get_instance_proc =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
  return get_instance_proc ? "" : "the Vulkan loader has no vkGetInstanceProcAddr";
}

bool VulkanFunctions::load_instance(VkInstance i) {
  bool all = true;  // every one read, so that a destructor finds what was there
  auto get = [&](auto& f, const char* name) {
    f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(get_instance_proc(i, name));
    all = all && f != nullptr;
  };
  get(queue_families, "vkGetPhysicalDeviceQueueFamilyProperties");
  get(memory_properties, "vkGetPhysicalDeviceMemoryProperties");
  get(get_device_proc, "vkGetDeviceProcAddr");
  get(destroy_instance, "vkDestroyInstance");
  return all;
}

bool VulkanFunctions::load_device(VkDevice d) {
  bool all = true;  // every one read, so that a destructor finds what was there
  auto get = [&](auto& f, const char* name) {
    f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(get_device_proc(d, name));
    all = all && f != nullptr;
  };
  get(destroy_device, "vkDestroyDevice");
  get(get_queue, "vkGetDeviceQueue");
  get(create_command_pool, "vkCreateCommandPool");
  get(destroy_command_pool, "vkDestroyCommandPool");
  get(allocate_command_buffers, "vkAllocateCommandBuffers");
  get(begin_command_buffer, "vkBeginCommandBuffer");
  get(end_command_buffer, "vkEndCommandBuffer");
  get(reset_command_buffer, "vkResetCommandBuffer");
  get(pipeline_barrier, "vkCmdPipelineBarrier");
  get(copy_buffer_to_image, "vkCmdCopyBufferToImage");
  get(copy_image_to_buffer, "vkCmdCopyImageToBuffer");
  get(queue_submit, "vkQueueSubmit");
  get(create_fence, "vkCreateFence");
  get(destroy_fence, "vkDestroyFence");
  get(wait_for_fences, "vkWaitForFences");
  get(reset_fences, "vkResetFences");
  get(create_buffer, "vkCreateBuffer");
  get(destroy_buffer, "vkDestroyBuffer");
  get(buffer_requirements, "vkGetBufferMemoryRequirements");
  get(allocate_memory, "vkAllocateMemory");
  get(free_memory, "vkFreeMemory");
  get(bind_buffer_memory, "vkBindBufferMemory");
  get(map_memory, "vkMapMemory");
  get(device_wait_idle, "vkDeviceWaitIdle");
  return all;
}

}  // namespace handlab::xr
