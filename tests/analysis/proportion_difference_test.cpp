// Newcombe's hybrid score interval for a difference of proportions against R 4.2.2's
// Epi::ci.pd(method = "Nc") (Epi 2.47); the first seven are examples Newcombe (1998) worked.
#include "analysis/stats/proportion_difference.h"

#include <gtest/gtest.h>

namespace handlab::stats::proportion_difference_test {

TEST(NewcombeDifference, EqualsRsEpiCiPd) {
  struct Case {
    double hits_a, n_a, hits_b, n_b, low, high;
  };
  for (const Case& c : {
           Case{56, 70, 48, 80, 0.052431472402365, 0.333872654036906},
           Case{9, 10, 3, 10, 0.170522723934503, 0.809017973535488},
           Case{6, 7, 2, 7, 0.058227927482312, 0.806249637524228},
           Case{5, 56, 0, 29, -0.038137147903537, 0.192560013855112},
           Case{0, 10, 0, 20, -0.161125158052819, 0.277532799862889},
           Case{0, 10, 0, 10, -0.277532799862889, 0.277532799862889},
           Case{10, 10, 0, 20, 0.679086037141915, 1.0},
           // A map's closing in five repeats before and after: held every time, then in two,
           // in four; and the other way.
           Case{5, 5, 2, 5, 0.029789890791842, 0.882379225767352},
           Case{5, 5, 4, 5, -0.264324837583889, 0.624465370237475},
           Case{4, 5, 5, 5, -0.624465370237475, 0.264324837583889},
           Case{20, 20, 13, 20, 0.116638656140598, 0.567145723314764},
       }) {
    const ProportionDifference d = newcombe_difference(c.hits_a, c.n_a, c.hits_b, c.n_b);
    EXPECT_DOUBLE_EQ(d.difference, c.hits_a / c.n_a - c.hits_b / c.n_b);
    EXPECT_NEAR(d.low, c.low, 1e-12)
        << c.hits_a << "/" << c.n_a << " - " << c.hits_b << "/" << c.n_b;
    EXPECT_NEAR(d.high, c.high, 1e-12)
        << c.hits_a << "/" << c.n_a << " - " << c.hits_b << "/" << c.n_b;
  }
}

}  // namespace handlab::stats::proportion_difference_test
