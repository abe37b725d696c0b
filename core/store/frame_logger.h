// Per-frame records written to the study database off the simulation thread: log() encodes
// the frame and queues it (no database work, no lock held for long); a writer thread
// commits the queue in batches. Nothing is dropped: the queue grows if the disk stalls, and
// flush() returns once every logged frame is committed.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/store/frame_record.h"

namespace handlab::store {

class FrameLogger {
 public:
  // Opens its own connection to the study database at `path`.
  explicit FrameLogger(const std::string& path, std::size_t batch_frames = 64);
  ~FrameLogger();  // commits what is queued
  FrameLogger(const FrameLogger&) = delete;
  FrameLogger& operator=(const FrameLogger&) = delete;

  // Simulation thread: frame `seq` of trial `trial_id`.
  void log(std::int64_t trial_id, std::int64_t seq, const FrameRecord& frame);
  // Blocks until every frame logged so far is committed; rethrows the writer's error.
  void flush();
  std::size_t committed() const;

 private:
  struct Pending {
    std::int64_t trial_id = 0, seq = 0;
    double time = 0.0;
    std::vector<std::uint8_t> data;
  };
  void run(const std::string& path);

  std::size_t batch_frames_;
  mutable std::mutex mutex_;
  std::condition_variable wake_writer_, wake_caller_;
  std::vector<Pending> queue_;
  std::vector<std::vector<std::uint8_t>> spare_;  // buffers back from the writer
  std::size_t logged_ = 0, committed_ = 0;
  bool stop_ = false, flushing_ = false, ready_ = false;
  std::exception_ptr error_;
  std::thread writer_;
};

}  // namespace handlab::store
