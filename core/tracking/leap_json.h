// Reading Leap Motion JSON: frames as the Leap service sends them over its WebSocket
// (protocol v6), and LeapJS Playback recordings (formatVersion 0.1, 1 and 2 "packed";
// plain .json or LZ-string-compressed .json.lz). Millimetres become metres here.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/tracking/tracked_frame.h"
#include "core/util/json_value.h"

namespace handlab::tracking {

struct RejectedFrame {
  std::size_t index;  // position in the file (0-based, after any key table)
  std::string reason;
};

struct Recording {
  std::string source;
  std::string format_version;        // as the file gives it ("0.1", "2", "handlab 1")
  std::size_t frames_in_file = 0;    // frame records the file holds
  std::vector<TrackedFrame> frames;  // those that were read and passed the checks
  std::vector<RejectedFrame> rejected;
};

// Parses one v6 frame object (a WebSocket message or an element of a v0.1/v1 recording).
// Returns nullopt with `error` set when the frame is unusable (missing fields, NaN, absurd
// values); a frame with no hands is valid.
std::optional<TrackedFrame> parse_leap_frame(const util::JsonValue& frame, std::string* error);
std::optional<TrackedFrame> parse_leap_message(std::string_view json, std::string* error);

// The frame as the Leap service would send it over its WebSocket (protocol v6, millimetres):
// what parse_leap_message reads back to the same frame, up to the rounding of the unit
// change. Fields the frame marks as derived are left out, as the source had them.
std::string leap_message(const TrackedFrame& frame, double frame_rate_hz);

// Parses a LeapJS Playback document (decompressed). Frames that fail their checks, and frames
// whose timestamps repeat or go backwards, are listed in `rejected`, the rest kept. Throws
// std::runtime_error when the document itself is unusable (not JSON, no frames array).
Recording parse_playback(std::string_view json, const std::string& source);

}  // namespace handlab::tracking
