// A thread-safe queue of tracked frames that is a FrameSource: a live tracker pushes from
// its (Qt) thread, the session runner pulls from its own.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>

#include "core/tracking/frame_source.h"

namespace handlab::live {

class FrameQueue : public tracking::FrameSource {
 public:
  explicit FrameQueue(std::chrono::milliseconds wait = std::chrono::milliseconds(1000),
                      std::size_t capacity = 1024)
      : wait_(wait), capacity_(capacity) {}

  void push(tracking::TrackedFrame frame) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (frames_.size() == capacity_)
        frames_.pop_front();  // a stalled consumer sees the newest frames
      frames_.push_back(std::move(frame));
    }
    ready_.notify_one();
  }
  void close() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }
  // Waits up to the configured time for a frame; nullopt when closed and empty, or on timeout.
  std::optional<tracking::TrackedFrame> next() override {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, wait_, [&] { return !frames_.empty() || closed_; });
    if (frames_.empty()) return std::nullopt;
    tracking::TrackedFrame frame = std::move(frames_.front());
    frames_.pop_front();
    return frame;
  }

 private:
  std::chrono::milliseconds wait_;
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<tracking::TrackedFrame> frames_;
  bool closed_ = false;
};

}  // namespace handlab::live
