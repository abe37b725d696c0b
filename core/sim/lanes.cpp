#include "core/sim/lanes.h"

#include <stdexcept>

namespace handlab::sim {
namespace {
constexpr int kSpins = 20000;  // some tens of microseconds of polling before a thread sleeps
}

Lanes::Lanes(int count) : count_(count) {
  if (count < 1) throw std::invalid_argument("Lanes: at least one lane");
  for (int lane = 1; lane < count; ++lane) threads_.emplace_back([this, lane] { serve(lane); });
}

Lanes::~Lanes() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void Lanes::run(const std::function<void(int lane)>& work) {
  if (count_ == 1) {
    work(0);
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    work_ = &work;
    running_.store(count_ - 1, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  work(0);
  for (int spin = 0; running_.load(std::memory_order_acquire) != 0; ++spin)
    if (spin > kSpins) std::this_thread::yield();
}

void Lanes::serve(int lane) {
  long seen = 0;
  for (;;) {
    int spin = 0;
    while (generation_.load(std::memory_order_acquire) == seen && !stopping_ && spin < kSpins)
      ++spin;
    if (generation_.load(std::memory_order_acquire) == seen) {
      std::unique_lock lock(mutex_);
      start_.wait(lock, [&] { return stopping_ || generation_.load() != seen; });
    }
    if (stopping_) return;
    const std::function<void(int)>* work;
    {
      // work_ was set under the mutex before the generation moved on.
      const std::lock_guard lock(mutex_);
      seen = generation_.load();
      work = work_;
    }
    (*work)(lane);
    running_.fetch_sub(1, std::memory_order_release);
  }
}

}  // namespace handlab::sim
