// Wilson's score interval against R 4.2.2's prop.test(x, n, correct = FALSE)$conf.int.
#include "analysis/stats/wilson_interval.h"

#include <gtest/gtest.h>

namespace handlab::stats::wilson_interval_test {

TEST(WilsonInterval, EqualsRsPropTestWithoutCorrection) {
  struct Case {
    double hits, n, low, high;
  };
  for (const Case& c :
       {Case{0, 10, 0.0, 0.277532799862889}, Case{5, 10, 0.236593090512564, 0.763406909487436},
        Case{59, 60, 0.911448702724099, 0.997051840205214},
        Case{51, 60, 0.738854109302215, 0.919025594198323}}) {
    const ProportionInterval i = wilson_interval(c.hits, c.n);
    EXPECT_NEAR(i.low, c.low, 1e-12) << c.hits << " of " << c.n;
    EXPECT_NEAR(i.high, c.high, 1e-12) << c.hits << " of " << c.n;
  }
}

}  // namespace handlab::stats::wilson_interval_test
