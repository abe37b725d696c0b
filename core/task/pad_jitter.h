// A tracker's jitter as the grip feels it: how far a recording's jitter (tracker_jitter.h),
// laid on a pinch, moves each pad, and the two pads against each other: along the line
// between them (the squeeze changes) and across it (the shear that rolls a held cube), sampled
// at every step from the recording's start over one pass of it.
#pragma once

#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/task/finger_pads.h"
#include "core/task/tracker_jitter.h"

namespace handlab::sim {

struct PadJitter {
  double scale = 0.0;                       // times the recording's jitter
  double thumb_rms = 0.0, index_rms = 0.0;  // m: each pad's displacement from the pinch's
  // m: how far the index pad moves against the thumb's (the change of the one seen from the
  // other), along the line between them and across it
  double along_rms = 0.0, across_rms = 0.0;
  double relative_speed_rms = 0.0, relative_speed_max = 0.0;  // m/s: of that change
};

// `jitter` laid on `pinch` `scale` times at every `time_step` over one pass of the recording
// (PoseJitter::apply: the frame at or before each step; the step from the recording's last frame
// back to its first, which a longer run takes, is left out). Throws std::invalid_argument for a
// pad's bone not in `skeleton`, a time step not above 0 or a jitter shorter than two steps.
PadJitter pad_jitter(const hand::Skeleton& skeleton, const hand::HandPose& pinch,
                     const PinchPads& pads, const PoseJitter& jitter, double scale,
                     double time_step);

}  // namespace handlab::sim
