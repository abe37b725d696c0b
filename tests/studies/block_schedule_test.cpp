#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "studies/protocol/block_schedule.h"

namespace handlab::studies {
namespace {

TEST(BlockSchedule, EveryBlockHoldsEachConditionOnce) {
  const BlockSchedule s = randomized_block_schedule(2021, "P01", 4, 5);
  ASSERT_EQ(s.size(), 5u);
  for (auto order : s) {
    std::sort(order.begin(), order.end());
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
  }
}

TEST(BlockSchedule, ReproducibleAndPerParticipant) {
  EXPECT_EQ(randomized_block_schedule(2021, "P01", 4, 5),
            randomized_block_schedule(2021, "P01", 4, 5));
  EXPECT_NE(randomized_block_schedule(2021, "P01", 4, 5),
            randomized_block_schedule(2021, "P02", 4, 5));
  EXPECT_NE(randomized_block_schedule(2021, "P01", 4, 5),
            randomized_block_schedule(7, "P01", 4, 5));
}

TEST(BlockSchedule, OrdersAreSpreadOverAllPermutations) {
  // 24 orders of 4 conditions; over 2,400 blocks each should appear ~100 times.
  std::map<std::vector<int>, int> seen;
  for (int p = 0; p < 480; ++p) {
    const std::string id = std::string("P").append(std::to_string(p));
    for (const auto& order : randomized_block_schedule(1, id, 4, 5)) ++seen[order];
  }
  EXPECT_EQ(seen.size(), 24u);
  for (const auto& [order, count] : seen) EXPECT_NEAR(count, 100, 40);
}

TEST(BlockSchedule, RejectsEmptyDesigns) {
  EXPECT_THROW(randomized_block_schedule(1, "P01", 0, 5), std::invalid_argument);
}

}  // namespace
}  // namespace handlab::studies
