// How much a hand tracker's joint positions jitter from frame to frame, measured from its
// recordings: the noise a simulated participant adds to the skeleton it sends.
#pragma once

#include <vector>

#include "core/tracking/tracked_frame.h"

namespace handlab::studies {

struct TrackingJitter {
  double sd = 0.0;       // m: per axis of a joint position, white noise at the tracker's rate
  long samples = 0;      // second differences it rests on
  double rate_hz = 0.0;  // the frames' median rate
};

// White noise of SD s adds 6 s^2 to the variance of a position's second difference, while a
// hand's own motion adds a |acceleration| dt^2 that is small at the tracker's rate. Robust:
// the median absolute second difference over every joint, axis and frame triple of one hand
// (frames 1.5 median intervals apart or more break a run), as 1.4826 MAD / sqrt(6). The
// motion's share makes this an upper bound.
TrackingJitter measure_tracking_jitter(const std::vector<tracking::TrackedFrame>& frames);

}  // namespace handlab::studies
