// The OpenXR loader, opened when first asked for (libopenxr_loader.so.1): handlab runs where no
// loader is installed, and says so where a headset is asked for. Every OpenXR function comes
// through the loader's xrGetInstanceProcAddr, the one symbol read from the library.
#pragma once

#include <string>
#include <vector>

#define XR_NO_PROTOTYPES  // every function comes through the loader (below)
#include <openxr/openxr.h>

namespace handlab::xr {

class OpenXrLoader {
 public:
  // The process's loader: opened once; `available()` false, and `error()` why, where it is
  // not installed.
  static const OpenXrLoader& instance();

  bool available() const { return get_proc_ != nullptr; }
  const std::string& error() const { return error_; }

  // The function `name` of `instance` (XR_NULL_HANDLE for the global functions); nullptr
  // where the loader or the runtime does not have it.
  PFN_xrVoidFunction function(XrInstance instance, const char* name) const;

  template <typename Pfn>
  Pfn get(XrInstance instance, const char* name) const {
    return reinterpret_cast<Pfn>(function(instance, name));
  }

 private:
  OpenXrLoader();
  PFN_xrGetInstanceProcAddr get_proc_ = nullptr;
  std::string error_;
};

// An OpenXR input or output structure, zeroed, of its type.
template <typename T>
T xr_struct(XrStructureType type) {
  T t{};
  t.type = type;
  return t;
}

// An instance of the runtime the loader finds, named "handlab", OpenXR 1.0, with `extensions`
// enabled.
XrResult create_instance(const OpenXrLoader& loader, const std::vector<const char*>& extensions,
                         XrInstance* instance);

// XR_ERROR_RUNTIME_UNAVAILABLE and the like, or the number where the name is not known.
std::string result_name(XrResult result);

}  // namespace handlab::xr
