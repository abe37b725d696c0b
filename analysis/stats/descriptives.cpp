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

double timing_quantile(std::vector<double> values, double probability) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return quantile_type7(values, probability);
}

Descriptives describe(std::vector<double> values) {
  Descriptives d;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  d.n = int(values.size());
  d.mean = d.sd = d.se = d.median = d.q1 = d.q3 = d.min = d.max = nan;
  if (values.empty()) return d;
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / d.n;
  if (d.n > 1) {
    double ss = 0.0;
    for (double v : values) ss += (v - d.mean) * (v - d.mean);
    d.sd = std::sqrt(ss / (d.n - 1));
    d.se = d.sd / std::sqrt(double(d.n));
  }
  // Only a few order statistics are needed: select them in increasing order, each within
  // what the previous selection left above it, instead of sorting everything.
  const std::size_t last = values.size() - 1;
  std::vector<std::size_t> wanted = {0, last};
  for (double p : {0.25, 0.5, 0.75}) {
    const auto lo = std::size_t(std::floor(double(last) * p));
    wanted.push_back(lo);
    wanted.push_back(std::min(lo + 1, last));
  }
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  auto from = values.begin();
  std::vector<double> order_statistic(values.size(), nan);
  for (std::size_t k : wanted) {
    std::nth_element(from, values.begin() + std::ptrdiff_t(k), values.end());
    order_statistic[k] = values[k];
    from = values.begin() + std::ptrdiff_t(k) + 1;
  }
  auto quantile = [&](double p) {
    const double h = double(last) * p;
    const auto lo = std::size_t(std::floor(h));
    const std::size_t hi = std::min(lo + 1, last);
    return order_statistic[lo] + (h - double(lo)) * (order_statistic[hi] - order_statistic[lo]);
  };
  d.median = quantile(0.5);
  d.q1 = quantile(0.25);
  d.q3 = quantile(0.75);
  d.min = order_statistic[0];
  d.max = order_statistic[last];
  return d;
}

}  // namespace handlab::stats
