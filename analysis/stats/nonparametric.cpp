#include "analysis/stats/nonparametric.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "analysis/stats/distributions.h"

namespace handlab::stats {
namespace {

// Average ranks (1-based) of values, ties sharing the mean of their ranks; also returns
// sum over tie groups of t^3 - t.
std::vector<double> average_ranks(const std::vector<double>& values, double* tie_term) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  double ties = 0.0;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) ++j;
    const double rank = 0.5 * double(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) ranks[order[k]] = rank;
    const double t = double(j - i + 1);
    ties += t * t * t - t;
    i = j + 1;
  }
  if (tie_term) *tie_term = ties;
  return ranks;
}

}  // namespace

FriedmanResult friedman_test(const Eigen::MatrixXd& blocks) {
  const int n = int(blocks.rows()), k = int(blocks.cols());
  if (n < 1 || k < 2)
    throw std::invalid_argument("friedman_test needs at least one block and two conditions");
  FriedmanResult r;
  r.rank_sums.assign(std::size_t(k), 0.0);
  double ties = 0.0;
  for (int i = 0; i < n; ++i) {
    std::vector<double> row(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) row[std::size_t(j)] = blocks(i, j);
    double t = 0.0;
    const auto ranks = average_ranks(row, &t);
    ties += t;
    for (int j = 0; j < k; ++j) r.rank_sums[std::size_t(j)] += ranks[std::size_t(j)];
  }
  double spread = 0.0;
  for (double rj : r.rank_sums) spread += (rj - n * (k + 1) / 2.0) * (rj - n * (k + 1) / 2.0);
  r.chisq = 12.0 * spread / (n * k * (k + 1.0) - ties / (k - 1.0));
  r.df = k - 1.0;
  r.p = chi_squared_upper_tail(r.chisq, r.df);
  r.kendall_w = r.chisq / (n * (k - 1.0));
  r.n = n;
  return r;
}

double psignrank(double v, int n, bool lower_tail) {
  double x = std::round(v + 1e-7);
  const double max_sum = n * (n + 1.0) / 2.0;
  if (x < 0) return lower_tail ? 0.0 : 1.0;
  if (x >= max_sum) return lower_tail ? 1.0 : 0.0;
  // Number of subsets of {1..n} with each sum, by dynamic programming.
  std::vector<double> counts(std::size_t(max_sum) + 1, 0.0);
  counts[0] = 1.0;
  for (int r = 1; r <= n; ++r)
    for (long s = long(max_sum); s >= r; --s) counts[std::size_t(s)] += counts[std::size_t(s - r)];
  // As R: sum the smaller tail directly (the distribution is symmetric) for accuracy.
  const double f = std::exp(-n * std::numbers::ln2);
  double p = 0.0;
  if (x <= max_sum / 2.0) {
    for (long i = 0; i <= long(x); ++i) p += counts[std::size_t(i)] * f;
  } else {
    x = max_sum - x;
    for (long i = 0; i < long(x); ++i) p += counts[std::size_t(i)] * f;
    lower_tail = !lower_tail;
  }
  return lower_tail ? p : 0.5 - p + 0.5;
}

WilcoxonResult wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size())
    throw std::invalid_argument("wilcoxon_signed_rank: x and y differ in length");
  std::vector<double> d;
  bool zeros = false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double diff = x[i] - y[i];
    if (diff == 0.0)
      zeros = true;
    else
      d.push_back(diff);
  }
  WilcoxonResult r;
  r.n = int(d.size());
  std::vector<double> magnitude(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) magnitude[i] = std::abs(d[i]);
  double tie_term = 0.0;
  const auto ranks = average_ranks(magnitude, &tie_term);
  r.v = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] > 0) r.v += ranks[i];
  const bool ties = tie_term > 0.0;
  const double n = r.n;
  r.exact = r.n < 50 && !ties && !zeros;
  if (r.exact) {
    const double p =
        r.v > n * (n + 1) / 4 ? psignrank(r.v - 1, r.n, false) : psignrank(r.v, r.n, true);
    r.p = std::min(1.0, 2.0 * p);
    return r;
  }
  const double z0 = r.v - n * (n + 1) / 4;
  const double sigma = std::sqrt(n * (n + 1) * (2 * n + 1) / 24 - tie_term / 48);
  const double correction = z0 > 0 ? 0.5 : z0 < 0 ? -0.5 : 0.0;
  const double z = (z0 - correction) / sigma;  // 0/0 = NaN when every difference is zero
  r.p = std::isnan(z) ? std::numeric_limits<double>::quiet_NaN()
                      : std::min(1.0, 2.0 * std::min(normal_upper_tail(z), normal_upper_tail(-z)));
  return r;
}

}  // namespace handlab::stats
