// Reading any recording handlab knows by its name: LeapJS Playback .json / .json.lz, and
// handlab's own binary recordings (.hlrec), which keep frames exactly as they were.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/tracking/leap_json.h"

namespace handlab::tracking {

// Throws std::runtime_error naming the file when nothing usable can be read from it.
Recording read_recording(const std::string& path);

// handlab's own frame encoding (little-endian, doubles kept bit for bit): what the study
// database stores per frame, and the records of a .hlrec file.
std::vector<std::uint8_t> encode_frame(const TrackedFrame& frame);
TrackedFrame decode_frame(const std::uint8_t* data, std::size_t size, std::size_t* consumed);

void write_hlrec(const std::vector<TrackedFrame>& frames, const std::string& path);

}  // namespace handlab::tracking
