// The newest of the frames another thread publishes (a headset's frame loop locating the
// hands), as a live frame source: next() takes it once, wait_for_frame() waits for one.
#pragma once

#include <condition_variable>
#include <mutex>

#include "core/tracking/frame_source.h"

namespace handlab::tracking {

class LatestFrames : public LiveFrameSource {
 public:
  void publish(TrackedFrame frame);
  void finish();  // no more frames will come

  std::optional<TrackedFrame> next() override;
  bool wait_for_frame(std::chrono::steady_clock::time_point deadline) override;
  bool ended() const override;

 private:
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::optional<TrackedFrame> newest_;
  bool ended_ = false;
};

}  // namespace handlab::tracking
