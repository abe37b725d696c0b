// Fork-join over a fixed number of lanes: run(work) calls work(0) on the calling thread and
// work(1..n-1) on threads that wait between calls, and returns when all have finished. The
// simulator splits its per-tet loops this way, each lane into its own buffers, summed in lane
// order afterwards, so that results depend on the lane count and never on timing. Calls come
// a few hundred microseconds apart within a step: a waiting thread spins briefly before it
// sleeps, and the caller spins for the others to finish, since waking a sleeping thread costs
// about as much as the work split.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace handlab::sim {

class Lanes {
 public:
  explicit Lanes(int count);
  ~Lanes();
  Lanes(const Lanes&) = delete;
  Lanes& operator=(const Lanes&) = delete;

  int count() const { return count_; }
  // `work` must not throw.
  void run(const std::function<void(int lane)>& work);

  // The half-open range of [0, n) that lane `lane` takes.
  std::pair<int, int> range(int lane, int n) const {
    return {int(long(n) * lane / count_), int(long(n) * (lane + 1) / count_)};
  }

 private:
  void serve(int lane);

  int count_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_;
  const std::function<void(int)>* work_ = nullptr;
  std::atomic<long> generation_{0};
  std::atomic<int> running_{0};
  std::atomic<bool> stopping_{false};
};

}  // namespace handlab::sim
