// Boost.Math upper tails against closed forms that hold exactly for particular degrees of
// freedom, written so that the reference itself loses no precision in the far tail.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/stats/distributions.h"

namespace handlab::stats {
namespace {

constexpr double kRel = 1e-12;

void expect_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, kRel * std::abs(expected)) << "expected " << expected;
}

TEST(Distributions, TUpperTailOneDfIsCauchy) {
  for (double t : {0.1, 0.5, 1.0, 2.5, 10.0, 1e3}) {
    expect_rel(t_upper_tail(t, 1), std::atan(1.0 / t) / std::numbers::pi);
  }
}

TEST(Distributions, TUpperTailTwoDf) {
  // P(T > t) = 1 / (s (s + t)), s = sqrt(2 + t^2), for two degrees of freedom.
  for (double t : {0.0, 0.3, 1.0, 4.0, 50.0, 1e4}) {
    const double s = std::sqrt(2.0 + t * t);
    expect_rel(t_upper_tail(t, 2), 1.0 / (s * (s + t)));
  }
}

TEST(Distributions, FWithTwoNumeratorDf) {
  // P(F > f) = (1 + 2 f / d2)^(-d2 / 2) for F(2, d2).
  for (double d2 : {1.0, 4.0, 19.0, 76.0}) {
    for (double f : {0.2, 1.0, 8.78, 40.0}) {
      expect_rel(f_upper_tail(f, 2, d2), std::pow(1.0 + 2.0 * f / d2, -d2 / 2.0));
    }
  }
}

TEST(Distributions, FWithOneNumeratorDfIsTwoSidedT) {
  for (double d2 : {1.0, 2.0}) {
    for (double t : {0.5, 2.0, 9.0}) {
      const double expected = d2 == 1.0 ? 2.0 * std::atan(1.0 / t) / std::numbers::pi
                                        : 2.0 / (std::sqrt(2 + t * t) * (std::sqrt(2 + t * t) + t));
      expect_rel(f_upper_tail(t * t, 1, d2), expected);
      expect_rel(t_two_sided(-t, d2), expected);
    }
  }
}

TEST(Distributions, ChiSquaredTwoDfIsExponential) {
  for (double x : {0.1, 1.0, 11.143, 100.0})
    expect_rel(chi_squared_upper_tail(x, 2), std::exp(-x / 2));
}

TEST(Distributions, NormalUpperTail) {
  for (double z : {-2.0, 0.0, 1.96, 8.0})
    expect_rel(normal_upper_tail(z), 0.5 * std::erfc(z / std::sqrt(2.0)));
}

TEST(Distributions, EdgeCases) {
  EXPECT_EQ(f_upper_tail(0.0, 3, 10), 1.0);
  EXPECT_EQ(f_upper_tail(INFINITY, 3, 10), 0.0);
  EXPECT_TRUE(std::isnan(f_upper_tail(NAN, 3, 10)));
  EXPECT_TRUE(std::isnan(f_upper_tail(2.0, 0, 10)));
  EXPECT_TRUE(std::isnan(t_upper_tail(1.0, -1)));
}

}  // namespace
}  // namespace handlab::stats
