// Upper-tail probabilities of the distributions the tests use (Boost.Math underneath),
// computed directly as upper tails so that small p values keep their precision.
#pragma once

namespace handlab::stats {

double f_upper_tail(double f, double df1, double df2);  // P(F > f)
double t_upper_tail(double t, double df);               // P(T > t)
double t_two_sided(double t, double df);                // P(|T| > |t|)
double chi_squared_upper_tail(double x, double df);     // P(X > x)
double normal_upper_tail(double z);                     // P(Z > z)
double t_upper_quantile(double p, double df);           // t with P(T > t) = p

}  // namespace handlab::stats
