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

  using Clock = std::chrono::steady_clock;

  void push(tracking::TrackedFrame frame) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (frames_.size() == capacity_) {
        frames_.pop_front();  // a stalled consumer sees the newest frames
        arrivals_.pop_front();
      }
      frames_.push_back(std::move(frame));
      arrivals_.push_back(Clock::now());
    }
    ready_.notify_one();
  }
  // Without waiting: the newest frame and when it arrived, the older ones discarded (their
  // count added to `superseded`); nullopt when none came since the last call.
  std::optional<tracking::TrackedFrame> take_newest(Clock::time_point* arrival, long* superseded) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frames_.empty()) return std::nullopt;
    if (superseded) *superseded += long(frames_.size()) - 1;
    if (arrival) *arrival = arrivals_.back();
    tracking::TrackedFrame frame = std::move(frames_.back());
    frames_.clear();
    arrivals_.clear();
    return frame;
  }
  // Returns once a frame is queued (true), or at `deadline` or when closed (false).
  bool wait_for_frame(Clock::time_point deadline) {
    std::unique_lock<std::mutex> lock(mutex_);
    return ready_.wait_until(lock, deadline, [&] { return !frames_.empty() || closed_; }) &&
           !frames_.empty();
  }
  void clear() {
    const std::lock_guard<std::mutex> lock(mutex_);
    frames_.clear();
    arrivals_.clear();
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
    arrivals_.pop_front();
    return frame;
  }

 private:
  std::chrono::milliseconds wait_;
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<tracking::TrackedFrame> frames_;
  std::deque<Clock::time_point> arrivals_;
  bool closed_ = false;
};

}  // namespace handlab::live
