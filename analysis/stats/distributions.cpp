#include "analysis/stats/distributions.h"

#include <cmath>
#include <limits>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace handlab::stats {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Boost computes in long double by default; double is accurate to a few ulp here (the tests
// hold these tails to 1e-12 of closed forms) and several times faster.
using Policy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

}  // namespace

double f_upper_tail(double f, double df1, double df2) {
  if (std::isnan(f) || !(df1 > 0) || !(df2 > 0)) return kNaN;
  if (f <= 0) return 1.0;
  if (std::isinf(f)) return 0.0;
  return boost::math::cdf(
      boost::math::complement(boost::math::fisher_f_distribution<double, Policy>(df1, df2), f));
}

double t_upper_tail(double t, double df) {
  if (std::isnan(t) || !(df > 0)) return kNaN;
  if (std::isinf(t)) return t > 0 ? 0.0 : 1.0;
  return boost::math::cdf(
      boost::math::complement(boost::math::students_t_distribution<double, Policy>(df), t));
}

double t_two_sided(double t, double df) {
  const double upper = t_upper_tail(std::abs(t), df);
  return std::isnan(upper) ? kNaN : std::min(1.0, 2.0 * upper);
}

double chi_squared_upper_tail(double x, double df) {
  if (std::isnan(x) || !(df > 0)) return kNaN;
  if (x <= 0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return boost::math::cdf(
      boost::math::complement(boost::math::chi_squared_distribution<double, Policy>(df), x));
}

double normal_upper_tail(double z) {
  if (std::isnan(z)) return kNaN;
  if (std::isinf(z)) return z > 0 ? 0.0 : 1.0;
  return boost::math::cdf(
      boost::math::complement(boost::math::normal_distribution<double, Policy>(), z));
}

double t_upper_quantile(double p, double df) {
  if (std::isnan(p) || !(df > 0) || p <= 0 || p >= 1) return kNaN;
  return boost::math::quantile(
      boost::math::complement(boost::math::students_t_distribution<double, Policy>(df), p));
}

}  // namespace handlab::stats
