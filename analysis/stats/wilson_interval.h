// Wilson's score interval for a binomial proportion (Wilson 1927): right at 0 and 1, where
// p +- 1.96 SE is not.
#pragma once

namespace handlab::stats {

struct ProportionInterval {
  double low = 0.0, high = 1.0;
};

// The 95 % interval of `hits` of `n` (n > 0).
ProportionInterval wilson_interval(double hits, double n);

}  // namespace handlab::stats
