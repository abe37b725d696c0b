// Rank tests as R's stats package computes them: friedman.test and the paired
// wilcox.test with its defaults.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace handlab::stats {

struct FriedmanResult {
  double chisq, df, p;
  double kendall_w;  // chisq / (n (k - 1))
  int n;             // blocks (participants)
  std::vector<double> rank_sums;
};

// blocks x conditions, no missing values. Ranks within each block with ties averaged; the
// statistic carries the ties correction.
FriedmanResult friedman_test(const Eigen::MatrixXd& blocks);

struct WilcoxonResult {
  double v;    // sum of the ranks of positive differences x - y
  int n;       // pairs with a non-zero difference
  bool exact;  // exact distribution (n < 50, no ties, no zeros) or normal approximation
  double p;    // two-sided; NaN when every difference is zero
};

// Paired signed-rank test, wilcox.test(x, y, paired = TRUE): zero differences dropped; the
// exact p when fewer than 50 pairs remain and there are no ties or zeros, otherwise the
// normal approximation with tie-corrected variance and continuity correction. Ties are
// judged on exact doubles, as R does.
WilcoxonResult wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y);

// P(V <= v) (or P(V > v) when !lower_tail) of the signed-rank statistic for n pairs,
// as R's psignrank.
double psignrank(double v, int n, bool lower_tail = true);

}  // namespace handlab::stats
