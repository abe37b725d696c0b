#include "core/tracking/latest_frames.h"

namespace handlab::tracking {

void LatestFrames::publish(TrackedFrame frame) {
  {
    std::lock_guard lock(mutex_);
    newest_ = std::move(frame);
  }
  arrived_.notify_all();
}

void LatestFrames::finish() {
  {
    std::lock_guard lock(mutex_);
    ended_ = true;
  }
  arrived_.notify_all();
}

std::optional<TrackedFrame> LatestFrames::next() {
  std::lock_guard lock(mutex_);
  std::optional<TrackedFrame> f;
  f.swap(newest_);
  return f;
}

bool LatestFrames::wait_for_frame(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  return arrived_.wait_until(lock, deadline, [&] { return newest_.has_value() || ended_; }) &&
         newest_.has_value();
}

bool LatestFrames::ended() const {
  std::lock_guard lock(mutex_);
  return ended_;
}

}  // namespace handlab::tracking
