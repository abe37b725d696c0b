#include "core/task/grasp_closing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace handlab::sim {
namespace {

// Three significant digits, as the command line would take them back.
std::string number(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

}  // namespace

const std::vector<ClosingFactor>& closing_factors() {
  constexpr double kDegree = M_PI / 180.0;
  static const std::vector<ClosingFactor> factors = {
      {"over_closure",
       "mm",
       &GraspClosing::over_closure,
       1e-3,
       {0, 3, 5, 10, 15, 20, 25, 30},
       {15}},
      {"tilt_yaw",
       "deg",
       &GraspClosing::tilt_yaw,
       kDegree,
       {-30, -20, -10, 0, 10, 20, 30},
       {-15, 15}},
      {"tilt_pitch",
       "deg",
       &GraspClosing::tilt_pitch,
       kDegree,
       {-30, -20, -10, 0, 10, 20, 30},
       {-15, 15}},
      {"offset_along",
       "side",
       &GraspClosing::offset_along,
       1.0,
       {-0.4, -0.3, -0.2, -0.1, 0, 0.1, 0.2, 0.3, 0.4},
       {-0.2, 0.2}},
      {"lead", "ms", &GraspClosing::lead_s, 1e-3, {-200, -100, -50, 0, 50, 100, 200}, {-100, 100}},
      {"closing_speed", "cm/s", &GraspClosing::closing_speed, 1e-2, {2, 5, 10, 20, 30}, {2, 16}},
      // From the script's gentle 0.6 to 12 m/s^2, above a brisk lift of a light object.
      {"lift_acceleration",
       "m/s2",
       &GraspClosing::lift_acceleration,
       1.0,
       {0.6, 1.5, 3, 6, 12},
       {6}},
      {"hold", "s", &GraspClosing::hold_s, 1.0, {1, 5, 10}, {}},
      {"jitter", "x", &GraspClosing::jitter, 1.0, {0, 1, 2, 4, 8}, {4}},
  };
  return factors;
}

const ClosingFactor& closing_factor(const std::string& name) {
  const auto& factors = closing_factors();
  const auto f = std::find_if(factors.begin(), factors.end(),
                              [&](const ClosingFactor& c) { return c.name == name; });
  if (f != factors.end()) return *f;
  std::string names;
  for (const ClosingFactor& c : factors) names += (names.empty() ? "" : ", ") + c.name;
  throw std::invalid_argument("no closing factor '" + name + "' (" + names + ")");
}

void set_closing_factor(GraspClosing& closing, const std::string& name, double value) {
  const ClosingFactor* f = &closing_factor(name);
  // The grid's range, the speed and hold above zero.
  const double lo = std::min(f->levels.front(), 0.0), hi = f->levels.back();
  const bool positive =
      f->name == "closing_speed" || f->name == "hold" || f->name == "lift_acceleration";
  // 0 in a map's JSON values is the script's own speed, lift or hold: on the command line, the
  // factor left out.
  if (positive && !(value > 0 && value <= hi))
    throw std::invalid_argument(name + " must be above 0 and at most " + number(hi) + " " +
                                f->unit + " (left out: the script's), not " + number(value));
  if (!(value >= lo && value <= hi))
    throw std::invalid_argument(name + " must be from " + number(lo) + " to " + number(hi) + " " +
                                f->unit + ", not " + number(value));
  closing.*(f->field) = value * f->scale;
}

bool within_half_of_ranges(const GraspClosing& closing) {
  const GraspClosing standard;
  for (const ClosingFactor& f : closing_factors()) {
    if (f.pair_levels.empty() || closing.*(f.field) == standard.*(f.field)) continue;
    const auto [low, high] = std::minmax_element(f.pair_levels.begin(), f.pair_levels.end());
    const double from = f.levels.front() >= 0 ? std::min(*low, f.levels.front()) : *low;
    const double value = closing.*(f.field) / f.scale;
    if (value < from - 1e-9 || value > *high + 1e-9) return false;
  }
  return true;
}

std::string describe_level(const ClosingFactor& factor, double level) {
  return factor.name + " " + number(level) + " " + factor.unit;
}

std::string describe(const GraspClosing& closing) {
  const GraspClosing standard;
  std::string text;
  for (const ClosingFactor& f : closing_factors()) {
    const double value = closing.*(f.field);
    if (value == standard.*(f.field)) continue;
    text += (text.empty() ? "" : ", ") + describe_level(f, value / f.scale);
  }
  return text.empty() ? "the scripted pinch" : text;
}

}  // namespace handlab::sim
