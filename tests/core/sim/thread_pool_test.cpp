// The simulator's fork-join thread pool (core/sim/thread_pool.h): every worker runs once a
// call, on its own share, the call returning only when all have finished; many calls in a row, as a
// step makes.
#include <chrono>
#include <numeric>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/sim/thread_pool.h"

namespace handlab::sim {
namespace {

TEST(ThreadPool, EachWorkerRunsItsShareOnceACall) {
  for (int count : {1, 2, 3}) {
    ThreadPool pool(count);
    std::vector<int> visits(1001, 0);
    std::vector<long> sums(std::size_t(count), 0);
    for (int call = 0; call < 2000; ++call)
      pool.run([&](int worker) {
        const auto [begin, end] = pool.share(worker, int(visits.size()));
        for (int i = begin; i < end; ++i) {
          ++visits[std::size_t(i)];
          sums[std::size_t(worker)] += i;
        }
      });
    for (int v : visits) ASSERT_EQ(v, 2000) << count << " workers";
    EXPECT_EQ(std::accumulate(sums.begin(), sums.end(), 0L), 2000L * 1000 * 1001 / 2);
  }
  EXPECT_THROW(ThreadPool(0), std::invalid_argument);
}

// A worker sees what the caller wrote before the call; the caller, after it, what workers wrote.
TEST(ThreadPool, WritesAreSeenAcrossTheCall) {
  ThreadPool pool(3);
  int before = 0;
  std::vector<int> written(3, 0);
  for (int call = 1; call <= 5000; ++call) {
    before = call;
    pool.run([&](int worker) { written[std::size_t(worker)] = before; });
    for (int w : written) ASSERT_EQ(w, call);
  }
}

// Calls further apart than a worker polls for: each finds the workers asleep and wakes them,
// and the pool is destroyed with them asleep.
TEST(ThreadPool, WakesWorkersThatSleptBetweenCalls) {
  ThreadPool pool(2);
  std::vector<int> calls(2, 0);
  for (int call = 1; call <= 5; ++call) {
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
    pool.run([&](int worker) { ++calls[std::size_t(worker)]; });
    ASSERT_EQ(calls, std::vector<int>(2, call));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(3));
}

}  // namespace
}  // namespace handlab::sim
