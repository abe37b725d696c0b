#include "studies/session/session_control.h"

#include <utility>

namespace handlab::studies {

void SessionControl::set_paused(bool paused) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    paused_ = paused;
  }
  changed_.notify_all();
}

void SessionControl::request_stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
}

void SessionControl::decide(TrialDecision decision) {
  const std::lock_guard<std::mutex> lock(mutex_);
  decisions_.push_back(std::move(decision));
}

bool SessionControl::hold_while_paused() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (paused_ && !stop_ && holding) {
    lock.unlock();
    holding();
    lock.lock();
  }
  changed_.wait(lock, [&] { return !paused_ || stop_; });
  return !stop_;
}

std::vector<TrialDecision> SessionControl::take_decisions() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(decisions_, {});
}

}  // namespace handlab::studies
