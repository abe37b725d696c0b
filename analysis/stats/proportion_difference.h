// The difference of two independent binomial proportions with Newcombe's hybrid score
// interval (Newcombe 1998, Statistics in Medicine 17:873-890, method 10): each proportion's
// Wilson interval carried to the difference, right where one lies at 0 or 1, as a map's
// closing held in every repeat does.
#pragma once

#include "analysis/stats/wilson_interval.h"

namespace handlab::stats {

struct ProportionDifference {
  double difference = 0.0;        // hits_a / n_a - hits_b / n_b
  double low = -1.0, high = 1.0;  // its 95 % interval
};

// a - b for `hits_a` of `n_a` and `hits_b` of `n_b` (n_a, n_b > 0).
ProportionDifference newcombe_difference(double hits_a, double n_a, double hits_b, double n_b);

}  // namespace handlab::stats
