#include "core/xr/openxr_display.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/xr/hand_trackers.h"
#include "core/xr/openxr_functions.h"
#include "core/xr/vulkan_functions.h"

namespace handlab::xr {

namespace {

const char* state_name(XrSessionState s) {
  switch (s) {
    case XR_SESSION_STATE_IDLE:
      return "idle";
    case XR_SESSION_STATE_READY:
      return "ready";
    case XR_SESSION_STATE_SYNCHRONIZED:
      return "synchronized";
    case XR_SESSION_STATE_VISIBLE:
      return "visible";
    case XR_SESSION_STATE_FOCUSED:
      return "focused";
    case XR_SESSION_STATE_STOPPING:
      return "stopping";
    case XR_SESSION_STATE_LOSS_PENDING:
      return "loss pending";
    case XR_SESSION_STATE_EXITING:
      return "exiting";
    default:
      return "unknown";
  }
}

render::ViewCamera camera_of(const XrView& v) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = Eigen::Quaternionf(v.pose.orientation.w, v.pose.orientation.x,
                                     v.pose.orientation.y, v.pose.orientation.z)
                      .normalized()
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3f(v.pose.position.x, v.pose.position.y, v.pose.position.z);
  return render::eye_camera(pose, v.fov.angleLeft, v.fov.angleRight, v.fov.angleDown,
                            v.fov.angleUp);
}

}  // namespace

struct OpenXrDisplay::Session {
  // A host-visible buffer, mapped.
  struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* data = nullptr;
  };
  struct Eye {
    XrSwapchain swapchain = XR_NULL_HANDLE;
    std::vector<XrSwapchainImageVulkan2KHR> images;
    HostBuffer upload, read_back;
  };

  OpenXrFunctions xr;
  VulkanFunctions vk;
  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  XrSession session = XR_NULL_HANDLE;
  XrSpace space = XR_NULL_HANDLE;
  VkInstance vk_instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::int64_t format = 0;
  bool bgra = false;  // the swapchain's bytes are B, G, R, A
  int width = 0, height = 0;
  std::array<Eye, 2> eyes;
  std::string runtime;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false, ended = false;
  XrTime first_time = 0;
  DisplayCounts counts;
  HandSink hand_sink;
  HandTrackers hands;
  std::int64_t hand_frames = 0;

  ~Session();
  std::string create_instance(int max_eye_width);
  std::string create_vulkan();
  std::string create_commands();
  std::string create_session();
  std::string create_swapchains();
  bool host_buffer(VkDeviceSize size, VkBufferUsageFlags usage, HostBuffer& out);
  void handle_events();
  bool draw_views(XrTime time, const EyeDrawing& draw, DisplayFrame* out,
                  std::array<XrCompositionLayerProjectionView, 2>& projected);
  bool draw_eye(int e, const XrView& view, const EyeDrawing& draw, DisplayFrame* out);
  bool copy_through(VkImage image, const Eye& eye);
};

OpenXrDisplay::Session::~Session() {
  // Vulkan's functions may be missing where loading them failed half way.
  if (device != VK_NULL_HANDLE && vk.destroy_device && vk.device_wait_idle) {
    vk.device_wait_idle(device);
    for (Eye& e : eyes)
      for (HostBuffer* b : {&e.upload, &e.read_back}) {
        if (b->buffer) vk.destroy_buffer(device, b->buffer, nullptr);
        if (b->memory) vk.free_memory(device, b->memory, nullptr);
      }
    if (fence) vk.destroy_fence(device, fence, nullptr);
    if (pool) vk.destroy_command_pool(device, pool, nullptr);
  }
  if (hands.created()) hands.destroy(xr);
  for (Eye& e : eyes)
    if (e.swapchain != XR_NULL_HANDLE) xr.destroy_swapchain(e.swapchain);
  if (space != XR_NULL_HANDLE) xr.destroy_space(space);
  if (session != XR_NULL_HANDLE) xr.destroy_session(session);
  if (device != VK_NULL_HANDLE && vk.destroy_device) vk.destroy_device(device, nullptr);
  if (vk_instance != VK_NULL_HANDLE && vk.destroy_instance)
    vk.destroy_instance(vk_instance, nullptr);
  if (instance != XR_NULL_HANDLE && xr.destroy_instance) xr.destroy_instance(instance);
}

std::string OpenXrDisplay::Session::create_instance(int max_eye_width) {
  const OpenXrLoader& loader = OpenXrLoader::instance();
  if (!loader.available()) return loader.error();
  std::vector<const char*> extensions = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  if (hand_sink) extensions.push_back("XR_EXT_hand_tracking");
  XrResult r = xr::create_instance(loader, extensions, &instance);
  if (XR_FAILED(r))
    return "no OpenXR runtime drawing with Vulkan (XR_KHR_vulkan_enable2): " + result_name(r);
  if (!xr.load(loader, instance) || !xr.create_vulkan_device)
    return "the OpenXR runtime lacks a function a headset display needs";
  auto properties = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  if (XR_SUCCEEDED(xr.instance_properties(instance, &properties))) runtime = properties.runtimeName;
  auto system_info = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  if (XR_FAILED(r = xr.get_system(instance, &system_info, &system)))
    return "no headset: " + result_name(r);
  std::uint32_t count = 0;
  xr.configuration_views(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &count,
                         nullptr);
  std::vector<XrViewConfigurationView> views(
      count, xr_struct<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
  if (count != 2 ||
      XR_FAILED(xr.configuration_views(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO,
                                       count, &count, views.data())))
    return "the headset has no stereo view";
  width = int(views[0].recommendedImageRectWidth);
  height = int(views[0].recommendedImageRectHeight);
  if (max_eye_width > 0 && width > max_eye_width) {
    height = std::max(1, height * max_eye_width / width);
    width = max_eye_width;
  }
  return "";
}

std::string OpenXrDisplay::Session::create_vulkan() {
  if (std::string e = vk.open_library(); !e.empty()) return e;
  auto requirements =
      xr_struct<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
  if (XR_FAILED(xr.vulkan_requirements(instance, system, &requirements)))
    return "the runtime gave no Vulkan requirements";
  auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "handlab";
  app.apiVersion = VK_API_VERSION_1_1;
  auto vk_create = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  vk_create.pApplicationInfo = &app;
  auto create = xr_struct<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
  create.systemId = system;
  create.pfnGetInstanceProcAddr = vk.get_instance_proc;
  create.vulkanCreateInfo = &vk_create;
  VkResult vr = VK_SUCCESS;
  if (XR_FAILED(xr.create_vulkan_instance(instance, &create, &vk_instance, &vr)) ||
      vr != VK_SUCCESS)
    return "the runtime made no Vulkan instance (VkResult " + std::to_string(int(vr)) + ")";
  if (!vk.load_instance(vk_instance)) return "Vulkan lacks a function the display needs";
  auto device_info =
      xr_struct<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
  device_info.systemId = system;
  device_info.vulkanInstance = vk_instance;
  if (XR_FAILED(xr.vulkan_device(instance, &device_info, &physical)))
    return "the runtime named no Vulkan device";
  std::uint32_t families = 0;
  vk.queue_families(physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vk.queue_families(physical, &families, props.data());
  const auto graphics = std::find_if(
      props.begin(), props.end(),
      [](const VkQueueFamilyProperties& p) { return (p.queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0; });
  if (graphics == props.end()) return "the Vulkan device has no graphics queue";
  queue_family = std::uint32_t(graphics - props.begin());
  const float priority = 1.0f;
  auto queue_info = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queue_info.queueFamilyIndex = queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  auto vk_device = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  vk_device.queueCreateInfoCount = 1;
  vk_device.pQueueCreateInfos = &queue_info;
  auto create_device =
      xr_struct<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
  create_device.systemId = system;
  create_device.pfnGetInstanceProcAddr = vk.get_instance_proc;
  create_device.vulkanPhysicalDevice = physical;
  create_device.vulkanCreateInfo = &vk_device;
  if (XR_FAILED(xr.create_vulkan_device(instance, &create_device, &device, &vr)) ||
      vr != VK_SUCCESS)
    return "the runtime made no Vulkan device (VkResult " + std::to_string(int(vr)) + ")";
  if (!vk.load_device(device)) return "Vulkan lacks a function the display needs";
  vk.get_queue(device, queue_family, 0, &queue);
  return create_commands();
}

// The command buffer and fence the eyes' copies are recorded into and waited on.
std::string OpenXrDisplay::Session::create_commands() {
  auto pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family;
  auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  auto alloc =
      vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  alloc.commandBufferCount = 1;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  if (vk.create_command_pool(device, &pool_info, nullptr, &pool) != VK_SUCCESS ||
      (alloc.commandPool = pool, vk.allocate_command_buffers(device, &alloc, &commands)) !=
          VK_SUCCESS ||
      vk.create_fence(device, &fence_info, nullptr, &fence) != VK_SUCCESS)
    return "no Vulkan command buffer";
  return "";
}

std::string OpenXrDisplay::Session::create_session() {
  auto binding = xr_struct<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
  binding.instance = vk_instance;
  binding.physicalDevice = physical;
  binding.device = device;
  binding.queueFamilyIndex = queue_family;
  binding.queueIndex = 0;
  auto info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  info.next = &binding;
  info.systemId = system;
  XrResult r = xr.create_session(instance, &info, &session);
  if (XR_FAILED(r)) return "the OpenXR runtime made no session: " + result_name(r);
  auto space_info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  space_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  space_info.poseInReferenceSpace.orientation.w = 1.0f;
  if (XR_FAILED(r = xr.create_space(session, &space_info, &space)))
    return "no LOCAL space: " + result_name(r);
  return create_swapchains();
}

bool OpenXrDisplay::Session::host_buffer(VkDeviceSize size, VkBufferUsageFlags usage,
                                         HostBuffer& out) {
  auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = size;
  info.usage = usage;
  if (vk.create_buffer(device, &info, nullptr, &out.buffer) != VK_SUCCESS) return false;
  VkMemoryRequirements needs;
  vk.buffer_requirements(device, out.buffer, &needs);
  VkPhysicalDeviceMemoryProperties memory;
  vk.memory_properties(physical, &memory);
  const VkMemoryPropertyFlags wanted =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  alloc.allocationSize = needs.size;
  alloc.memoryTypeIndex = memory.memoryTypeCount;
  for (std::uint32_t t = 0; t < memory.memoryTypeCount; ++t)
    if ((needs.memoryTypeBits & (1u << t)) &&
        (memory.memoryTypes[t].propertyFlags & wanted) == wanted) {
      alloc.memoryTypeIndex = t;
      break;
    }
  return alloc.memoryTypeIndex < memory.memoryTypeCount &&
         vk.allocate_memory(device, &alloc, nullptr, &out.memory) == VK_SUCCESS &&
         vk.bind_buffer_memory(device, out.buffer, out.memory, 0) == VK_SUCCESS &&
         vk.map_memory(device, out.memory, 0, size, 0, &out.data) == VK_SUCCESS;
}

std::string OpenXrDisplay::Session::create_swapchains() {
  std::uint32_t count = 0;
  xr.swapchain_formats(session, 0, &count, nullptr);
  std::vector<std::int64_t> formats(count);
  xr.swapchain_formats(session, count, &count, formats.data());
  // 8-bit sRGB, as handlab's pictures are; B, G, R order where the runtime offers only that.
  for (std::int64_t f : {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB})
    if (!format && std::find(formats.begin(), formats.end(), f) != formats.end()) format = f;
  if (!format) return "the runtime offers no 8-bit sRGB swapchain";
  bgra = format == VK_FORMAT_B8G8R8A8_SRGB;
  const VkDeviceSize bytes = VkDeviceSize(width) * VkDeviceSize(height) * 4;
  for (Eye& eye : eyes) {
    auto info = xr_struct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT | XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT |
                      XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
    info.format = format;
    info.sampleCount = 1;
    info.width = std::uint32_t(width);
    info.height = std::uint32_t(height);
    info.faceCount = info.arraySize = info.mipCount = 1;
    if (XrResult r = xr.create_swapchain(session, &info, &eye.swapchain); XR_FAILED(r))
      return "no swapchain: " + result_name(r);
    std::uint32_t images = 0;
    xr.swapchain_images(eye.swapchain, 0, &images, nullptr);
    eye.images.assign(images,
                      xr_struct<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
    xr.swapchain_images(eye.swapchain, images, &images,
                        reinterpret_cast<XrSwapchainImageBaseHeader*>(eye.images.data()));
    if (!host_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, eye.upload) ||
        !host_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, eye.read_back))
      return "no Vulkan memory for the eyes' pictures";
  }
  return "";
}

void OpenXrDisplay::Session::handle_events() {
  auto event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  while (xr.poll_event(instance, &event) == XR_SUCCESS) {
    if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
      state = reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state;
      if (state == XR_SESSION_STATE_READY) {
        auto begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
        begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        running = XR_SUCCEEDED(xr.begin_session(session, &begin));
      } else if (state == XR_SESSION_STATE_STOPPING) {
        xr.end_session(session);
        running = false;
      } else if (state == XR_SESSION_STATE_EXITING || state == XR_SESSION_STATE_LOSS_PENDING) {
        ended = true;
      }
    } else if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      ended = true;
    }
    event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
  }
}

// The picture into the image, and the image back out, in one submission; false where Vulkan
// failed.
bool OpenXrDisplay::Session::copy_through(VkImage image, const Eye& eye) {
  auto barrier = vk_struct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  auto transition = [&](VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                        VkAccessFlags dst) {
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcAccessMask = src;
    barrier.dstAccessMask = dst;
    vk.pipeline_barrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1, &barrier);
  };
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {std::uint32_t(width), std::uint32_t(height), 1};
  auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk.reset_command_buffer(commands, 0);
  vk.begin_command_buffer(commands, &begin);
  // An acquired colour image is the application's in COLOR_ATTACHMENT_OPTIMAL, and goes back so.
  transition(VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
             VK_ACCESS_TRANSFER_WRITE_BIT);
  vk.copy_buffer_to_image(commands, eye.upload.buffer, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          1, &region);
  transition(VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
             VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  vk.copy_image_to_buffer(commands, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          eye.read_back.buffer, 1, &region);
  transition(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
             VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  // The read-back buffer's bytes made visible to the host that reads them after the fence.
  auto to_host = vk_struct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
  to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_host.buffer = eye.read_back.buffer;
  to_host.size = VK_WHOLE_SIZE;
  vk.pipeline_barrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                      nullptr, 1, &to_host, 0, nullptr);
  if (vk.end_command_buffer(commands) != VK_SUCCESS) return false;
  auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  vk.reset_fences(device, 1, &fence);
  return vk.queue_submit(queue, 1, &submit, fence) == VK_SUCCESS &&
         vk.wait_for_fences(device, 1, &fence, VK_TRUE, UINT64_MAX) == VK_SUCCESS;
}

// The eye drawn, copied into an acquired image and read back; false where no image was had or
// the copy failed (the image, if acquired, is released).
bool OpenXrDisplay::Session::draw_eye(int e, const XrView& view, const EyeDrawing& draw,
                                      DisplayFrame* out) {
  Eye& eye = eyes[std::size_t(e)];
  const render::ViewCamera camera = camera_of(view);
  const render::Image picture = draw(e, camera, width, height);
  auto* upload = static_cast<std::uint8_t*>(eye.upload.data);
  std::memcpy(upload, picture.rgba.data(),
              std::min(picture.rgba.size(), std::size_t(width) * height * 4));
  if (bgra)
    for (std::size_t i = 0; i < std::size_t(width) * height; ++i)
      std::swap(upload[4 * i], upload[4 * i + 2]);
  std::uint32_t index = 0;
  auto acquire = xr_struct<XrSwapchainImageAcquireInfo>(XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO);
  if (XR_FAILED(xr.acquire_image(eye.swapchain, &acquire, &index))) return false;
  auto wait = xr_struct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
  wait.timeout = XR_INFINITE_DURATION;
  auto release = xr_struct<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
  const bool copied = XR_SUCCEEDED(xr.wait_image(eye.swapchain, &wait)) &&
                      copy_through(eye.images[index].image, eye);
  if (copied && out) {
    render::Image& back = out->read_back[std::size_t(e)];
    back.width = width;
    back.height = height;
    const auto* bytes = static_cast<const std::uint8_t*>(eye.read_back.data);
    back.rgba.assign(bytes, bytes + std::size_t(width) * height * 4);
    if (bgra)
      for (std::size_t i = 0; i < std::size_t(width) * height; ++i)
        std::swap(back.rgba[4 * i], back.rgba[4 * i + 2]);
    out->cameras[std::size_t(e)] = camera;
  }
  xr.release_image(eye.swapchain, &release);
  return copied;
}

std::unique_ptr<OpenXrDisplay> OpenXrDisplay::open(std::string& error, int max_eye_width,
                                                   HandSink hands) {
  auto s = std::make_unique<Session>();
  s->hand_sink = std::move(hands);
  error = s->create_instance(max_eye_width);
  if (error.empty()) error = s->create_vulkan();
  if (error.empty()) error = s->create_session();
  if (error.empty() && s->hand_sink) error = s->hands.create(s->xr, s->session);
  if (!error.empty()) return nullptr;
  return std::unique_ptr<OpenXrDisplay>(new OpenXrDisplay(std::move(s)));
}

OpenXrDisplay::OpenXrDisplay(std::unique_ptr<Session> session) : session_(std::move(session)) {}
OpenXrDisplay::~OpenXrDisplay() = default;

// Both eyes drawn into their swapchains for the frame at `time`, and their projection views;
// false (nothing to submit) where the views are not tracked or an image could not be had.
bool OpenXrDisplay::Session::draw_views(
    XrTime time, const EyeDrawing& draw, DisplayFrame* out,
    std::array<XrCompositionLayerProjectionView, 2>& projected) {
  std::array<XrView, 2> views{xr_struct<XrView>(XR_TYPE_VIEW), xr_struct<XrView>(XR_TYPE_VIEW)};
  auto locate = xr_struct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
  locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  locate.displayTime = time;
  locate.space = space;
  auto view_state = xr_struct<XrViewState>(XR_TYPE_VIEW_STATE);
  std::uint32_t count = 0;
  const XrViewStateFlags tracked =
      XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT;
  if (XR_FAILED(xr.locate_views(session, &locate, &view_state, 2, &count, views.data())) ||
      count != 2 || (view_state.viewStateFlags & tracked) != tracked)
    return false;
  for (int e = 0; e < 2; ++e) {
    if (!draw_eye(e, views[std::size_t(e)], draw, out)) return false;
    XrCompositionLayerProjectionView& p = projected[std::size_t(e)];
    p = xr_struct<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
    p.pose = views[std::size_t(e)].pose;
    p.fov = views[std::size_t(e)].fov;
    p.subImage.swapchain = eyes[std::size_t(e)].swapchain;
    p.subImage.imageRect = {{0, 0}, {width, height}};
  }
  return true;
}

bool OpenXrDisplay::frame(const EyeDrawing& draw, DisplayFrame* out) {
  Session& s = *session_;
  s.handle_events();
  if (s.ended) return false;
  if (!s.running) return true;  // not yet begun, or stopped: nothing to submit
  if (out) *out = {};
  auto state = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
  auto wait = xr_struct<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
  if (XR_FAILED(s.xr.wait_frame(s.session, &wait, &state))) return true;
  ++s.counts.waits;
  auto begin = xr_struct<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
  if (XR_FAILED(s.xr.begin_frame(s.session, &begin))) return true;
  ++s.counts.begins;
  if (s.first_time == 0) s.first_time = state.predictedDisplayTime;
  if (s.hands.created()) {
    tracking::TrackedFrame hands;
    hands.timestamp = double(state.predictedDisplayTime - s.first_time) * 1e-9;
    hands.id = ++s.hand_frames;
    hands.hands = s.hands.locate(s.xr, s.space, state.predictedDisplayTime);
    s.hand_sink(std::move(hands));
  }
  std::array<XrCompositionLayerProjectionView, 2> projected{};
  auto layer = xr_struct<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
  const XrCompositionLayerBaseHeader* layers[] = {
      reinterpret_cast<XrCompositionLayerBaseHeader*>(&layer)};
  auto end = xr_struct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
  end.displayTime = state.predictedDisplayTime;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  const bool drawn =
      state.shouldRender && s.draw_views(state.predictedDisplayTime, draw, out, projected);
  if (drawn) {
    layer.space = s.space;
    layer.viewCount = 2;
    layer.views = projected.data();
    end.layerCount = 1;
    end.layers = layers;
  }
  if (XR_SUCCEEDED(s.xr.end_frame(s.session, &end))) ++s.counts.ends;
  if (drawn) {
    ++s.counts.drawn;
    if (out) {
      out->drawn = true;
      out->time = double(state.predictedDisplayTime - s.first_time) * 1e-9;
    }
  }
  return true;
}

void OpenXrDisplay::request_exit() {
  if (session_->running) session_->xr.request_exit(session_->session);
}

int OpenXrDisplay::eye_width() const {
  return session_->width;
}
int OpenXrDisplay::eye_height() const {
  return session_->height;
}
std::string OpenXrDisplay::runtime_name() const {
  return session_->runtime;
}
std::string OpenXrDisplay::session_state() const {
  return state_name(session_->state);
}
DisplayCounts OpenXrDisplay::counts() const {
  return session_->counts;
}

}  // namespace handlab::xr
