#include "studies/session/openxr_tracker.h"

#include <memory>
#include <stdexcept>
#include <string>

#include "core/xr/openxr_hand_source.h"

namespace handlab::studies {

TrackerPtr openxr_tracker(const SessionHeadset* headset) {
  if (headset && headset->hands())
    return live_tracker("openxr " + headset->runtime_name() + " (the headset's hands)",
                        [frames = headset->hands()] { return xr::view_of(frames); });
  std::string error;
  std::shared_ptr<xr::OpenXrHandSource> source = xr::OpenXrHandSource::open(error);
  if (!source) throw std::runtime_error(error + " (docs/hmd.md)");
  return live_tracker("openxr " + source->runtime_name(), [source] { return xr::view_of(source); });
}

}  // namespace handlab::studies
