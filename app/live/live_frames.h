// A live tracker as the session's frame source (studies::live_tracker). It keeps when that
// frame arrived, for the app's latency figures, and counts the frames the session never
// used (superseded by a newer one before a step took them).
#pragma once

#include <atomic>
#include <memory>

#include "app/live/frame_queue.h"

namespace handlab::live {

struct LiveFrameStats {
  std::atomic<long> used{0}, superseded{0};
  // The arrival of the frame last handed to the session (steady clock, ns since epoch).
  std::atomic<long long> last_arrival_ns{0};
};

class LiveFrames : public tracking::LiveFrameSource {
 public:
  LiveFrames(FrameQueue& queue, std::shared_ptr<LiveFrameStats> stats)
      : queue_(queue), stats_(std::move(stats)) {
    queue_.clear();  // frames from before this trial are not this trial's
  }
  std::optional<tracking::TrackedFrame> next() override {
    FrameQueue::Clock::time_point arrival;
    long superseded = 0;
    auto frame = queue_.take_newest(&arrival, &superseded);
    if (frame) {
      stats_->used += 1;
      stats_->superseded += superseded;
      stats_->last_arrival_ns = arrival.time_since_epoch().count();
    }
    return frame;
  }
  bool wait_for_frame(std::chrono::steady_clock::time_point deadline) override {
    return queue_.wait_for_frame(deadline);
  }

 private:
  FrameQueue& queue_;
  std::shared_ptr<LiveFrameStats> stats_;
};

}  // namespace handlab::live
