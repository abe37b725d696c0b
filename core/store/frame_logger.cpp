#include "core/store/frame_logger.h"

#include <chrono>

#include "core/store/sqlite_database.h"

namespace handlab::store {

FrameLogger::FrameLogger(const std::string& path, std::size_t batch_frames)
    : batch_frames_(batch_frames ? batch_frames : 1) {
  writer_ = std::thread([this, path] { run(path); });
  // Opening errors surface here, not at the first frame.
  std::unique_lock lock(mutex_);
  wake_caller_.wait(lock, [&] { return ready_ || error_; });
  if (error_) {
    lock.unlock();
    writer_.join();
    std::rethrow_exception(error_);
  }
}

FrameLogger::~FrameLogger() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_writer_.notify_one();
  if (writer_.joinable()) writer_.join();
}

void FrameLogger::log(std::int64_t trial_id, std::int64_t seq, const FrameRecord& frame) {
  Pending p;
  p.trial_id = trial_id;
  p.seq = seq;
  p.time = frame.time;
  {
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    if (!spare_.empty()) {
      p.data = std::move(spare_.back());
      spare_.pop_back();
    }
  }
  encode_frame(frame, p.data);  // outside the lock
  bool wake;
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(p));
    ++logged_;
    wake = queue_.size() >= batch_frames_;
  }
  if (wake) wake_writer_.notify_one();
}

void FrameLogger::flush() {
  std::unique_lock lock(mutex_);
  const std::size_t target = logged_;
  flushing_ = true;
  wake_writer_.notify_one();
  wake_caller_.wait(lock, [&] { return committed_ >= target || error_; });
  flushing_ = false;
  if (error_) std::rethrow_exception(error_);
}

std::size_t FrameLogger::committed() const {
  std::lock_guard lock(mutex_);
  return committed_;
}

void FrameLogger::run(const std::string& path) {
  try {
    Database db(path, Database::Mode::kReadWrite);
    db.exec("PRAGMA busy_timeout = 10000");  // the session's own commits are short
    Statement insert = db.prepare("INSERT INTO frame (trial_id, seq, t, data) VALUES (?, ?, ?, ?)");
    {
      std::lock_guard lock(mutex_);
      ready_ = true;
    }
    wake_caller_.notify_all();
    std::vector<Pending> batch;
    while (true) {
      {
        std::unique_lock lock(mutex_);
        // Batches: wait for enough frames, a flush, a stop, or 50 ms.
        wake_writer_.wait_for(lock, std::chrono::milliseconds(50),
                              [&] { return stop_ || flushing_ || queue_.size() >= batch_frames_; });
        if (queue_.empty()) {
          if (stop_) return;
          continue;
        }
        batch.swap(queue_);
      }
      {
        Transaction t(db);
        for (const Pending& p : batch)
          insert.bind(1, p.trial_id).bind(2, p.seq).bind(3, p.time).bind_blob(4, p.data).run();
        t.commit();
      }
      {
        std::lock_guard lock(mutex_);
        committed_ += batch.size();
        for (Pending& p : batch)
          if (spare_.size() < 4 * batch_frames_) spare_.push_back(std::move(p.data));
      }
      batch.clear();
      wake_caller_.notify_all();
    }
  } catch (...) {
    {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
    wake_caller_.notify_all();
  }
}

}  // namespace handlab::store
