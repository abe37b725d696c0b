// The simulator's fork-join lanes (core/sim/lanes.h): every lane runs once a call, on its own
// range, the call returning only when all have finished; many calls in a row, as a step makes.
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "core/sim/lanes.h"

namespace handlab::sim {
namespace {

TEST(Lanes, EachLaneRunsItsRangeOnceACall) {
  for (int count : {1, 2, 3}) {
    Lanes lanes(count);
    std::vector<int> visits(1001, 0);
    std::vector<long> sums(std::size_t(count), 0);
    for (int call = 0; call < 2000; ++call)
      lanes.run([&](int lane) {
        const auto [begin, end] = lanes.range(lane, int(visits.size()));
        for (int i = begin; i < end; ++i) {
          ++visits[std::size_t(i)];
          sums[std::size_t(lane)] += i;
        }
      });
    for (int v : visits) ASSERT_EQ(v, 2000) << count << " lanes";
    EXPECT_EQ(std::accumulate(sums.begin(), sums.end(), 0L), 2000L * 1000 * 1001 / 2);
  }
  EXPECT_THROW(Lanes(0), std::invalid_argument);
}

// A lane sees what the caller wrote before the call; the caller, after it, what lanes wrote.
TEST(Lanes, WritesAreSeenAcrossTheCall) {
  Lanes lanes(3);
  int before = 0;
  std::vector<int> written(3, 0);
  for (int call = 1; call <= 5000; ++call) {
    before = call;
    lanes.run([&](int lane) { written[std::size_t(lane)] = before; });
    for (int w : written) ASSERT_EQ(w, call);
  }
}

}  // namespace
}  // namespace handlab::sim
