// A recording as a Leap gives it when it tracks the hand with low confidence (a hand partly
// out of view, fingers hiding each other): its joints jitter, a finger jumps to another pose
// for a few frames and back, and frames come at another rate. What retargeting is timed on
// besides the recordings as they are (docs/performance.md, "Retargeting"); deterministic for
// its seed.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tracking/tracked_frame.h"

namespace handlab::tracking {

struct Degradation {
  double joint_noise = 0.0;  // m: standard deviation of each joint coordinate's added noise
  // Each frame, each finger of each hand starts a jump with this chance: the finger turns
  // about its knuckle (MCP) by an angle drawn up to max_jump_angle about the palm's radial
  // axis (curling or straightening) for jump_frames frames.
  double jump_chance = 0.0;
  double max_jump_angle = 1.0;  // rad
  int jump_frames = 3;
  double rate_hz = 0.0;  // resampled to this frame rate (0: the recording's own)
  std::uint64_t seed = 1;
};

// The joints, palm position and wrist are degraded; the palm's orientation and any bone bases
// stay as recorded. Throws std::invalid_argument for a negative noise, a chance outside
// [0, 1], a jump of no frames or a negative rate.
std::vector<TrackedFrame> degrade(const std::vector<TrackedFrame>& frames,
                                  const Degradation& degradation);

}  // namespace handlab::tracking
