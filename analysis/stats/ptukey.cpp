// A port of the algorithm in R's nmath/ptukey.c: Gauss-Legendre quadrature over the
// chi distribution of the error standard deviation (16 points per interval) of the
// probability of the range of `cc` normals (wprob, 12 points per interval).
#include "analysis/stats/ptukey.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <vector>

namespace handlab::stats {
namespace {

double pnorm(double x, double mean = 0.0) {
  return 0.5 * std::erfc(-(x - mean) / std::numbers::sqrt2);
}

// x^n; by squaring when n is a small whole number (the number of means always is), which
// is several times cheaper than pow and as accurate to a few ulp.
double power(double x, double n) {
  if (n != std::floor(n) || n < 0 || n > 64) return std::pow(x, n);
  double result = 1.0;
  for (auto k = unsigned(n); k; k >>= 1, x *= x)
    if (k & 1u) result *= x;
  return result;
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
  pr_w = pr_w >= std::exp(kC2 / cc) ? power(pr_w, cc) : 0.0;

  const double intervals = w > kLarge ? 2.0 : 3.0;
  long double lower = qsqz;
  const double step = (kUpper - qsqz) / intervals;
  long double upper = lower + step;
  long double integral = 0.0;
  const double cc1 = cc - 1.0;
  const double rinsum_floor = std::exp(kC1 / cc1);
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
      if (rinsum >= rinsum_floor) {
        rinsum = aleg[j - 1] * std::exp(-0.5 * qexpo) * power(rinsum, cc1);
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
  pr_w = power(pr_w, rr);
  return pr_w >= 1.0 ? 1.0 : pr_w;
}

// R's outer integral runs over the chi-distributed error scale in intervals of this length.
double outer_interval_length(double df) {
  return df <= 100.0 ? 1.0 : df <= 800.0 ? 0.5 : df <= 5000.0 ? 0.25 : 0.125;
}

// The 16 Gauss-Legendre nodes of outer interval i that contribute (exp(t1) >= 9e-14), each
// as (weight, scale) with the node's term = W(q * scale) * weight, in R's order.
template <typename Visit>
void for_each_outer_node(double df, double ulen, int i, const Visit& visit) {
  constexpr int kNodes = 16, kHalf = 8;
  constexpr double kEps1 = -30.0;
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
  // Leading constant of the chi density of the error SD, on a log scale.
  const double f2 = df * 0.5;
  const double f2lf = f2 * std::log(df) - df * std::numbers::ln2 - std::lgamma(f2) + std::log(ulen);
  const double f21 = f2 - 1.0;
  const double ff4 = df * 0.25;
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
    if (t1 < kEps1) continue;  // exp(t1) < 9e-14 contributes nothing
    const double scale = kHalf < jj ? std::sqrt((xlegq[j] * ulen + twa1) * 0.5)
                                    : std::sqrt((-(xlegq[j] * ulen) + twa1) * 0.5);
    visit(alegq[j] * std::exp(t1), scale);
  }
}

// R's outer integral over the studentized error, with W(w) = wprob(w, ranges, means)
// supplied by the caller (exactly, or interpolated for a family of comparisons).
template <typename RangeProbability>
double ptukey_lower_with(double q, double means, double df, double ranges,
                         const RangeProbability& range_probability) {
  constexpr double kEps2 = 1.0e-14;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (std::isnan(q) || std::isnan(ranges) || std::isnan(means) || std::isnan(df)) return nan;
  if (q <= 0) return 0.0;
  if (df < 2 || ranges < 1 || means < 2) return nan;
  if (!std::isfinite(q)) return 1.0;
  if (df > 25000.0) return range_probability(q);

  const double ulen = outer_interval_length(df);
  double ans = 0.0, otsum = 0.0;
  for (int i = 1; i <= 50; ++i) {
    otsum = 0.0;
    for_each_outer_node(df, ulen, i, [&](double weight, double scale) {
      otsum += range_probability(q * scale) * weight;
    });
    // Stop once an interval adds < 1e-14, but integrate at least one unit of the left tail.
    if (i * ulen >= 1.0 && otsum <= kEps2) break;
    ans += otsum;
  }
  return ans > 1.0 ? 1.0 : ans;
}

}  // namespace

double ptukey_lower(double q, double means, double df, double ranges) {
  return ptukey_lower_with(q, means, df, ranges, [&](double w) { return wprob(w, ranges, means); });
}

double ptukey_upper(double q, double means, double df, double ranges) {
  const double lower = ptukey_lower(q, means, df, ranges);
  return std::isnan(lower) ? lower : 0.5 - lower + 0.5;
}

namespace {

// Chebyshev interpolant of f on [a, b] with n nodes.
struct Chebyshev {
  double a = 0, b = 1;
  std::vector<double> c;

  template <typename F>
  Chebyshev(double a_, double b_, int n, const F& f) : a(a_), b(b_), c(std::size_t(n)) {
    std::vector<double> values(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const double x = std::cos(std::numbers::pi * (k + 0.5) / n);
      values[std::size_t(k)] = f(0.5 * (b - a) * x + 0.5 * (b + a));
    }
    for (int j = 0; j < n; ++j) {
      double sum = 0.0;
      for (int k = 0; k < n; ++k)
        sum += values[std::size_t(k)] * std::cos(std::numbers::pi * j * (k + 0.5) / n);
      c[std::size_t(j)] = 2.0 * sum / n;
    }
  }

  double operator()(double w) const {  // Clenshaw
    const double x = (2.0 * w - a - b) / (b - a);
    double b1 = 0.0, b2 = 0.0;
    for (std::size_t j = c.size(); j-- > 1;) {
      const double t = 2.0 * x * b1 - b2 + c[j];
      b2 = b1;
      b1 = t;
    }
    return x * b1 - b2 + 0.5 * c[0];
  }
};

}  // namespace

// W(w) is smooth on (0, 3] and (3, 16) (R's wprob switches its quadrature at 3 and returns
// exactly 1 from 16 on): 32 pieces of width 0.5, each a 14-node Chebyshev interpolant,
// reproduce it to ~1e-15 and cost 14 terms an evaluation.
struct TukeyFamily::RangeTable {
  static constexpr double kWidth = 0.5;
  static constexpr int kPieces = 32, kNodes = 14;
  std::vector<Chebyshev> pieces;

  RangeTable(double means, double ranges) {
    for (int p = 0; p < kPieces; ++p)
      pieces.emplace_back(p * kWidth, (p + 1) * kWidth, kNodes,
                          [&](double w) { return wprob(w, ranges, means); });
  }
  double operator()(double w) const {
    if (w <= 0.0) return 0.0;
    if (w >= kPieces * kWidth) return 1.0;
    // Piece p covers (p w, (p + 1) w]; the boundary 3 belongs to the piece below it, as in wprob.
    const int p = std::min(kPieces - 1, int(std::ceil(w / kWidth)) - 1);
    return std::clamp(pieces[std::size_t(p)](w), 0.0, 1.0);
  }

  // W depends only on the number of means (and ranges): one table per process and size.
  static std::shared_ptr<const RangeTable> shared(double means, double ranges) {
    static std::mutex mutex;
    static std::map<std::pair<double, double>, std::shared_ptr<const RangeTable>> tables;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& table = tables[{means, ranges}];
    if (!table) table = std::make_shared<const RangeTable>(means, ranges);
    return table;
  }
};

// R's outer quadrature for a family's df, with every node's weight and scale precomputed.
struct TukeyFamily::OuterNodes {
  struct Node {
    double weight;  // alegq * exp(t1)
    double scale;   // qsqz = q * scale
  };
  std::vector<std::vector<Node>> intervals;
  std::vector<double> interval_start;  // i * ulen, for R's stopping rule
};

TukeyFamily::TukeyFamily(double means, double df, double ranges)
    : means_(means), df_(df), ranges_(ranges) {
  if (std::isnan(means) || std::isnan(df) || std::isnan(ranges) || df < 2 || ranges < 1 ||
      means < 2)
    return;
  table_ = RangeTable::shared(means, ranges);
  if (df > 25000.0) return;
  auto nodes = std::make_shared<OuterNodes>();
  const double ulen = outer_interval_length(df);
  for (int i = 1; i <= 50; ++i) {
    std::vector<OuterNodes::Node> interval;
    for_each_outer_node(df, ulen, i, [&](double weight, double scale) {
      interval.push_back({weight, scale});
    });
    nodes->intervals.push_back(std::move(interval));
    nodes->interval_start.push_back(i * ulen);
  }
  nodes_ = std::move(nodes);
}

double TukeyFamily::upper(double q) const {
  if (!table_ || std::isnan(q)) return std::numeric_limits<double>::quiet_NaN();
  if (q <= 0) return 1.0;
  if (!std::isfinite(q)) return 0.0;
  if (!nodes_) return 0.5 - (*table_)(q) + 0.5;
  double ans = 0.0;
  for (std::size_t i = 0; i < nodes_->intervals.size(); ++i) {
    double otsum = 0.0;
    for (const auto& node : nodes_->intervals[i]) otsum += (*table_)(q * node.scale) * node.weight;
    if (nodes_->interval_start[i] >= 1.0 && otsum <= 1.0e-14) break;
    ans += otsum;
  }
  return 0.5 - std::min(ans, 1.0) + 0.5;
}

}  // namespace handlab::stats
