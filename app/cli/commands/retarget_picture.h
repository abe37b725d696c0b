// The paper's Figure 3.3 for any recording: one pinch frame, the tracked hand, Naive's and
// Ours' intermediate hands side by side, drawn offscreen.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/hand/hand_shape.h"
#include "core/retarget/retargeter.h"
#include "core/tracking/recording_io.h"

namespace handlab::cli {

// Runs both strategies through the recording up to the frame (the one with the highest
// pinch strength unless `frame_id` is given) and writes the picture as PNG. Returns the
// frame's id.
std::int64_t write_retarget_picture(const tracking::Recording& recording, tracking::Side side,
                                    const hand::HandShape& shape,
                                    const retarget::Calibration& calibration,
                                    const tracking::TrackedHandFitter& fitter,
                                    std::optional<std::int64_t> frame_id, const std::string& path);

}  // namespace handlab::cli
