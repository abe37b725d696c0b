#include "analysis/stats/proportion_difference.h"

#include <cmath>

namespace handlab::stats {

ProportionDifference newcombe_difference(double hits_a, double n_a, double hits_b, double n_b) {
  const double a = hits_a / n_a, b = hits_b / n_b;
  const ProportionInterval ia = wilson_interval(hits_a, n_a), ib = wilson_interval(hits_b, n_b);
  ProportionDifference d;
  d.difference = a - b;
  d.low = d.difference - std::hypot(a - ia.low, ib.high - b);
  d.high = d.difference + std::hypot(ia.high - a, b - ib.low);
  return d;
}

}  // namespace handlab::stats
