#include "core/sim/thread_pool.h"

#include <stdexcept>

namespace handlab::sim {
namespace {
constexpr int kSpins = 20000;  // some tens of microseconds of polling before a thread sleeps
}

ThreadPool::ThreadPool(int workers) : workers_(workers) {
  if (workers < 1) throw std::invalid_argument("ThreadPool: at least one worker");
  for (int worker = 1; worker < workers; ++worker)
    threads_.emplace_back([this, worker] { serve(worker); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void ThreadPool::run(const std::function<void(int worker)>& work) {
  if (workers_ == 1) {
    work(0);
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    work_ = &work;
    running_.store(workers_ - 1, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  work(0);
  for (int spin = 0; running_.load(std::memory_order_acquire) != 0; ++spin)
    if (spin > kSpins) std::this_thread::yield();
}

void ThreadPool::serve(int worker) {
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
    (*work)(worker);
    running_.fetch_sub(1, std::memory_order_release);
  }
}

}  // namespace handlab::sim
