// Summary statistics of a sample, with R's conventions (sd with n - 1, quantile type 7).
#pragma once

#include <vector>

namespace handlab::stats {

struct Descriptives {
  int n = 0;
  double mean, sd, se, median, q1, q3, min, max;
};

Descriptives describe(std::vector<double> values);

// R's quantile(type = 7) of sorted values.
double quantile_type7(const std::vector<double>& sorted, double probability);
// The same of values in any order; 0 for none (a timing summary with nothing timed).
double timing_quantile(std::vector<double> values, double probability);

}  // namespace handlab::stats
