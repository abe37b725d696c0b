// Fork-join over a fixed number of worker threads: run(work) calls work(0) on the calling
// thread and work(1..n-1) on threads that wait between calls, and returns when all have
// finished. The simulator splits its per-tet loops this way, each worker's share into its own
// buffers, summed in worker order afterwards, so that results depend on the worker count and
// never on timing. Calls come up to a few hundred microseconds apart within a step: a waiting
// thread polls for half a millisecond before it sleeps (briefly, where the pool's threads have
// to share cores), and the caller polls for the others to finish, since waking a sleeping
// thread costs about as much as the work split.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace handlab::sim {

class ThreadPool {
 public:
  explicit ThreadPool(int workers);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int workers() const { return workers_; }
  // `work` must not throw.
  void run(const std::function<void(int worker)>& work);

  // The half-open share of [0, n) that worker `worker` takes.
  std::pair<int, int> share(int worker, int n) const {
    return {int(long(n) * worker / workers_), int(long(n) * (worker + 1) / workers_)};
  }

 private:
  void serve(int worker);
  // Workers poll only briefly for a while: the pool's threads were found to share cores.
  void back_off(std::chrono::steady_clock::time_point now);

  int workers_;
  // Whether each thread can have a core, and from when (steady clock ticks) workers may poll
  // long again after one of the pool's threads was found preempted.
  bool cores_enough_;
  std::atomic<std::chrono::steady_clock::rep> long_polls_from_{0};
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_;
  const std::function<void(int)>* work_ = nullptr;
  std::atomic<long> generation_{0};
  std::atomic<int> running_{0};
  std::atomic<bool> stopping_{false};
};

}  // namespace handlab::sim
