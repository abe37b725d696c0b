#include "analysis/stats/effect_size.h"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/distributions/non_central_t.hpp>

namespace handlab::stats {
namespace {

namespace bm = boost::math;

// The x in [lo, hi] with decreasing(x) = target, for a function that falls as x grows; `lo`
// when even lo's value is below the target. The bracket's top is doubled until it holds.
double solve_decreasing(const std::function<double(double)>& decreasing, double target, double lo,
                        double hi) {
  if (decreasing(lo) <= target) return lo;
  for (int k = 0; k < 200 && decreasing(hi) > target; ++k) hi = 2.0 * hi + 1.0;
  for (int k = 0; k < 200 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)); ++k) {
    const double mid = 0.5 * (lo + hi);
    (decreasing(mid) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void check_level(double level) {
  if (!(level > 0.0 && level < 1.0)) throw std::invalid_argument("a level is in (0, 1)");
}

}  // namespace

double partial_eta_squared(double f, double df1, double df2) {
  return f * df1 / (f * df1 + df2);
}

EffectInterval partial_eta_squared_interval(double f, double df1, double df2, double level) {
  check_level(level);
  if (!(f >= 0.0) || !(df1 > 0.0) || !(df2 > 0.0))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  // The cdf at f falls as the noncentrality grows.
  auto cdf = [&](double lambda) {
    return lambda <= 0.0 ? bm::cdf(bm::fisher_f(df1, df2), f)
                         : bm::cdf(bm::non_central_f(df1, df2, lambda), f);
  };
  const double tail = 0.5 * (1.0 - level);
  const double start = std::max(1.0, f * df1);
  const double low = solve_decreasing(cdf, 1.0 - tail, 0.0, start);
  const double high = solve_decreasing(cdf, tail, 0.0, start);
  auto eta = [&](double lambda) { return lambda / (lambda + df1 + df2 + 1.0); };
  return {eta(low), eta(high)};
}

double paired_dz(double t, double n) {
  return t / std::sqrt(n);
}

EffectInterval paired_dz_interval(double t, double df, double n, double level) {
  check_level(level);
  if (!std::isfinite(t) || !(df > 0.0) || !(n > 0.0))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  // The cdf at t falls as delta grows; delta is searched on [t - w, t + w], widened as needed.
  auto cdf = [&](double delta) { return bm::cdf(bm::non_central_t(df, delta), t); };
  const double tail = 0.5 * (1.0 - level);
  double w = 10.0 + std::abs(t);
  for (int k = 0; k < 60 && (cdf(t - w) < 1.0 - tail || cdf(t + w) > tail); ++k) w *= 2.0;
  auto shifted = [&](double x) { return cdf(x + t - w); };  // on [0, 2w]
  const double low = solve_decreasing(shifted, 1.0 - tail, 0.0, 2.0 * w) + t - w;
  const double high = solve_decreasing(shifted, tail, 0.0, 2.0 * w) + t - w;
  const double root_n = std::sqrt(n);
  return {low / root_n, high / root_n};
}

}  // namespace handlab::stats
