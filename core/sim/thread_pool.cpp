#include "core/sim/thread_pool.h"

#include <chrono>
#include <stdexcept>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace handlab::sim {
namespace {

// How long a waiting thread polls before it sleeps: longer than the serial stretches between
// a step's parallel calls (contacts, the line search's bookkeeping, the policy), so that within
// a step no call waits for a sleeping thread to be woken, which on this class of machine takes
// tens of microseconds; shorter than the gap between the 120 Hz steps of a live session, so
// that the thread sleeps between them.
constexpr auto kPollFor = std::chrono::microseconds(500);

void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Polls `waiting` until it turns false or kPollFor has passed; whether it turned false. It
// yields now and then, so that a thread it waits for that has no core of its own (more
// threads than cores) gets one.
template <typename Waiting>
bool poll(Waiting waiting) {
  const auto until = std::chrono::steady_clock::now() + kPollFor;
  for (int spin = 0; waiting(); ++spin) {
    relax();
    if (spin % 64 == 63) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::yield();
    }
  }
  return true;
}

}  // namespace

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
  auto others_running = [&] { return running_.load(std::memory_order_acquire) != 0; };
  while (!poll(others_running)) std::this_thread::yield();
}

void ThreadPool::serve(int worker) {
  long seen = 0;
  for (;;) {
    poll([&] { return generation_.load(std::memory_order_acquire) == seen && !stopping_; });
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
