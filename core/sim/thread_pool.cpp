#include "core/sim/thread_pool.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#if defined(__linux__)
#include <sched.h>
#endif

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace handlab::sim {
namespace {

// How long a worker polls for the next call before it sleeps: longer than the serial stretches
// between a step's parallel calls (up to about 0.15 ms: contacts, the line search, the
// policy), so that within a step no call waits for a sleeping thread to be woken, which on
// this class of machine takes tens of microseconds; shorter than the gap between the 120 Hz
// steps of a live session, so that it sleeps between them. A polling worker holds a core, so
// it polls that long only while the pool's threads have the cores to themselves: not where
// the pool has more threads than the process has cores, and not for kBackOff after a thread
// of the pool found itself preempted (a worker while it polled, the caller while it yielded
// to the workers: another process wanted the core, and the pool's threads then lose theirs
// for milliseconds at a time). Otherwise it polls briefly, as the caller does for the others
// to finish; a sleeping worker woken by the call preempts another process at once.
constexpr auto kPollFor = std::chrono::microseconds(500);
constexpr auto kBriefly = std::chrono::microseconds(5);
constexpr auto kBackOff = std::chrono::milliseconds(250);
// A gap this long between two looks at the clock, some microseconds apart when it runs, is a
// preemption.
constexpr auto kPreempted = std::chrono::microseconds(200);

void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

enum class Polled { kDone, kTimedOut, kPreempted };

// Polls `waiting` until it turns false or `how_long` has passed.
template <typename Waiting>
Polled poll(Waiting waiting, std::chrono::microseconds how_long) {
  auto last = std::chrono::steady_clock::now();
  const auto until = last + how_long;
  for (int spin = 0; waiting(); ++spin) {
    relax();
    if (spin % 64 == 63) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last > kPreempted) return Polled::kPreempted;
      if (now > until) return Polled::kTimedOut;
      last = now;
    }
  }
  return Polled::kDone;
}

// The cores this process may run on.
int usable_cores() {
#if defined(__linux__)
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
#endif
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

ThreadPool::ThreadPool(int workers) : workers_(workers), cores_enough_(workers <= usable_cores()) {
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

void ThreadPool::back_off(std::chrono::steady_clock::time_point now) {
  long_polls_from_.store((now + kBackOff).time_since_epoch().count(), std::memory_order_relaxed);
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
  // The others are at work: briefly polled, then yielded to, should one lack a core.
  auto others_running = [&] { return running_.load(std::memory_order_acquire) != 0; };
  if (poll(others_running, kBriefly) == Polled::kDone) return;
  // A yield that returns late gave the core to another thread: the pool's threads share cores.
  auto last = std::chrono::steady_clock::now();
  while (others_running()) {
    std::this_thread::yield();
    const auto now = std::chrono::steady_clock::now();
    if (now - last > kPreempted) back_off(now);
    last = now;
  }
}

void ThreadPool::serve(int worker) {
  long seen = 0;
  for (;;) {
    const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
    const bool alone = cores_enough_ && now >= long_polls_from_.load(std::memory_order_relaxed);
    const Polled polled =
        poll([&] { return generation_.load(std::memory_order_acquire) == seen && !stopping_; },
             alone ? kPollFor : kBriefly);
    if (polled == Polled::kPreempted) back_off(std::chrono::steady_clock::now());
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
