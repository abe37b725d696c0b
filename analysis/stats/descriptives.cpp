#include "analysis/stats/descriptives.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace handlab::stats {

double quantile_type7(const std::vector<double>& sorted, double probability) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double h = (double(sorted.size()) - 1.0) * probability;
  const auto lo = std::size_t(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - double(lo)) * (sorted[hi] - sorted[lo]);
}

Descriptives describe(std::vector<double> values) {
  Descriptives d;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  d.n = int(values.size());
  d.mean = d.sd = d.se = d.median = d.q1 = d.q3 = d.min = d.max = nan;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / d.n;
  if (d.n > 1) {
    double ss = 0.0;
    for (double v : values) ss += (v - d.mean) * (v - d.mean);
    d.sd = std::sqrt(ss / (d.n - 1));
    d.se = d.sd / std::sqrt(double(d.n));
  }
  d.median = quantile_type7(values, 0.5);
  d.q1 = quantile_type7(values, 0.25);
  d.q3 = quantile_type7(values, 0.75);
  d.min = values.front();
  d.max = values.back();
  return d;
}

}  // namespace handlab::stats
