#include "analysis/stats/wilson_interval.h"

#include <algorithm>
#include <cmath>

namespace handlab::stats {

ProportionInterval wilson_interval(double hits, double n) {
  const double p = hits / n;
  const double z = 1.959963984540054, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace handlab::stats
