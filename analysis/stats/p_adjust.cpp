#include "analysis/stats/p_adjust.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace handlab::stats {

std::vector<double> p_adjust_bonferroni(const std::vector<double>& p) {
  const auto m = double(std::count_if(p.begin(), p.end(), [](double x) { return !std::isnan(x); }));
  std::vector<double> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    out[i] = std::isnan(p[i]) ? p[i] : std::min(1.0, p[i] * m);
  return out;
}

std::vector<double> p_adjust_holm(const std::vector<double>& p) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isnan(p[i])) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  std::vector<double> out = p;
  const double m = double(order.size());
  double running = 0.0;
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    running = std::max(running, std::min(1.0, (m - double(rank)) * p[order[rank]]));
    out[order[rank]] = running;
  }
  return out;
}

}  // namespace handlab::stats
