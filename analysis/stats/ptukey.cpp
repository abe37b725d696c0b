// A port of the algorithm in R's nmath/ptukey.c: Gauss-Legendre quadrature over the
// chi distribution of the error standard deviation (16 points per interval) of the
// probability of the range of `cc` normals (wprob, 12 points per interval).
#include "analysis/stats/ptukey.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace handlab::stats {
namespace {

double pnorm(double x, double mean = 0.0) {
  return 0.5 * std::erfc(-(x - mean) / std::numbers::sqrt2);
}

// Probability that the range of cc standard normals is below w, raised to rr.
double wprob(double w, double rr, double cc) {
  constexpr int kNodes = 12, kHalf = 6;
  constexpr double kC1 = -30.0, kC2 = -50.0, kC3 = 60.0, kUpper = 8.0, kLarge = 3.0;
  static constexpr double xleg[kHalf] = {
      0.981560634246719250690549090149, 0.904117256370474856678465866119,
      0.769902674194304687036893833213, 0.587317954286617447296702418941,
      0.367831498998180193752691536644, 0.125233408511468915472441369464};
  static constexpr double aleg[kHalf] = {
      0.047175336386511827194615961485, 0.106939325995318430960254718194,
      0.160078328543346226334652529543, 0.203167426723065921749064455810,
      0.233492536538354808760849898925, 0.249147045813402785000562436043};

  const double qsqz = w * 0.5;
  if (qsqz >= kUpper) return 1.0;  // the integral's lower bound is then 1 - 5e-14

  // (2 Phi(w/2) - 1)^cc: the first term of Hartley's form.
  double pr_w = 2.0 * pnorm(qsqz) - 1.0;
  pr_w = pr_w >= std::exp(kC2 / cc) ? std::pow(pr_w, cc) : 0.0;

  const double intervals = w > kLarge ? 2.0 : 3.0;
  long double lower = qsqz;
  const double step = (kUpper - qsqz) / intervals;
  long double upper = lower + step;
  long double integral = 0.0;
  const double cc1 = cc - 1.0;
  for (double i = 1; i <= intervals; ++i) {
    long double sum = 0.0;
    const double a = double(0.5 * (upper + lower));
    const double b = double(0.5 * (upper - lower));
    for (int jj = 1; jj <= kNodes; ++jj) {
      int j;
      double xx;
      if (kHalf < jj) {
        j = kNodes - jj + 1;
        xx = xleg[j - 1];
      } else {
        j = jj;
        xx = -xleg[j - 1];
      }
      const double ac = a + b * xx;
      const double qexpo = ac * ac;
      if (qexpo > kC3) break;  // exp(-qexpo/2) < 9e-14: no contribution
      const double pplus = 2.0 * pnorm(ac);
      const double pminus = 2.0 * pnorm(ac, w);
      double rinsum = pplus * 0.5 - pminus * 0.5;
      if (rinsum >= std::exp(kC1 / cc1)) {
        rinsum = aleg[j - 1] * std::exp(-0.5 * qexpo) * std::pow(rinsum, cc1);
        sum += rinsum;
      }
    }
    sum *= 2.0 * b * cc / std::sqrt(2.0 * std::numbers::pi);
    integral += sum;
    lower = upper;
    upper += step;
  }
  pr_w += double(integral);
  if (pr_w <= std::exp(kC1 / rr)) return 0.0;
  pr_w = std::pow(pr_w, rr);
  return pr_w >= 1.0 ? 1.0 : pr_w;
}

}  // namespace

double ptukey_lower(double q, double means, double df, double ranges) {
  constexpr int kNodes = 16, kHalf = 8;
  constexpr double kEps1 = -30.0, kEps2 = 1.0e-14;
  static constexpr double xlegq[kHalf] = {
      0.989400934991649932596154173450, 0.944575023073232576077988415535,
      0.865631202387831743880467897712, 0.755404408355003033895101194847,
      0.617876244402643748446671764049, 0.458016777657227386342419442984,
      0.281603550779258913230460501460, 0.950125098376374401853193354250e-1};
  static constexpr double alegq[kHalf] = {
      0.271524594117540948517805724560e-1, 0.622535239386478928628438369944e-1,
      0.951585116824927848099251076022e-1, 0.124628971255533872052476282192,
      0.149595988816576732081501730547,    0.169156519395002538189312079030,
      0.182603415044923588866763667969,    0.189450610455068496285396723208};

  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (std::isnan(q) || std::isnan(ranges) || std::isnan(means) || std::isnan(df)) return nan;
  if (q <= 0) return 0.0;
  if (df < 2 || ranges < 1 || means < 2) return nan;
  if (!std::isfinite(q)) return 1.0;
  if (df > 25000.0) return wprob(q, ranges, means);

  // Leading constant of the chi density of the error SD, on a log scale.
  const double f2 = df * 0.5;
  double f2lf = f2 * std::log(df) - df * std::numbers::ln2 - std::lgamma(f2);
  const double f21 = f2 - 1.0;
  const double ff4 = df * 0.25;
  const double ulen = df <= 100.0 ? 1.0 : df <= 800.0 ? 0.5 : df <= 5000.0 ? 0.25 : 0.125;
  f2lf += std::log(ulen);

  double ans = 0.0, otsum = 0.0;
  for (int i = 1; i <= 50; ++i) {
    otsum = 0.0;
    const double twa1 = (2 * i - 1) * ulen;
    for (int jj = 1; jj <= kNodes; ++jj) {
      int j;
      double t1;
      if (kHalf < jj) {
        j = jj - kHalf - 1;
        t1 = f2lf + f21 * std::log(twa1 + xlegq[j] * ulen) - (xlegq[j] * ulen + twa1) * ff4;
      } else {
        j = jj - 1;
        t1 = f2lf + f21 * std::log(twa1 - xlegq[j] * ulen) + (xlegq[j] * ulen - twa1) * ff4;
      }
      if (t1 >= kEps1) {  // exp(t1) < 9e-14 contributes nothing
        const double qsqz = kHalf < jj ? q * std::sqrt((xlegq[j] * ulen + twa1) * 0.5)
                                       : q * std::sqrt((-(xlegq[j] * ulen) + twa1) * 0.5);
        otsum += wprob(qsqz, ranges, means) * alegq[j] * std::exp(t1);
      }
    }
    // Stop once an interval adds < 1e-14, but integrate at least one unit of the left tail.
    if (i * ulen >= 1.0 && otsum <= kEps2) break;
    ans += otsum;
  }
  return ans > 1.0 ? 1.0 : ans;
}

double ptukey_upper(double q, double means, double df, double ranges) {
  const double lower = ptukey_lower(q, means, df, ranges);
  return std::isnan(lower) ? lower : 0.5 - lower + 0.5;
}

}  // namespace handlab::stats
