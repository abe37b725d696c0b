#include "core/xr/openxr_loader.h"

#include <dlfcn.h>
#include <stdlib.h>

#include <cstdint>
#include <cstring>

#include <openxr/openxr_reflection.h>

namespace handlab::xr {

OpenXrLoader::OpenXrLoader() {
  // The loader writes its errors to stderr; handlab says what failed in one line of its own.
  // XR_LOADER_DEBUG set by the user (error, warn, info, all) still asks for the loader's log.
  setenv("XR_LOADER_DEBUG", "none", 0);
  void* library = dlopen("libopenxr_loader.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = dlerror();
    error_ = std::string("no OpenXR loader (libopenxr_loader.so.1, Debian's libopenxr-loader1): ") +
             (why ? why : "not found");
    return;
  }
  get_proc_ = reinterpret_cast<PFN_xrGetInstanceProcAddr>(dlsym(library, "xrGetInstanceProcAddr"));
  if (!get_proc_) error_ = "the OpenXR loader has no xrGetInstanceProcAddr";
  // The library stays loaded for the process: runtimes it loads live as long.
}

const OpenXrLoader& OpenXrLoader::instance() {
  static const OpenXrLoader loader;
  return loader;
}

PFN_xrVoidFunction OpenXrLoader::function(XrInstance instance, const char* name) const {
  if (!get_proc_) return nullptr;
  PFN_xrVoidFunction f = nullptr;
  return XR_SUCCEEDED(get_proc_(instance, name, &f)) ? f : nullptr;
}

XrResult create_instance(const OpenXrLoader& loader, const std::vector<const char*>& extensions,
                         XrInstance* instance) {
  auto create = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::strncpy(create.applicationInfo.applicationName, "handlab", XR_MAX_APPLICATION_NAME_SIZE - 1);
  create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  create.enabledExtensionCount = std::uint32_t(extensions.size());
  create.enabledExtensionNames = extensions.data();
  auto make = loader.get<PFN_xrCreateInstance>(XR_NULL_HANDLE, "xrCreateInstance");
  return make ? make(&create, instance) : XR_ERROR_RUNTIME_UNAVAILABLE;
}

std::string result_name(XrResult result) {
#define HANDLAB_XR_RESULT_CASE(name, value) \
  case name:                                \
    return #name;
  switch (result) { XR_LIST_ENUM_XrResult(HANDLAB_XR_RESULT_CASE) default : break; }
#undef HANDLAB_XR_RESULT_CASE
  return "XrResult " + std::to_string(int(result));
}

}  // namespace handlab::xr
