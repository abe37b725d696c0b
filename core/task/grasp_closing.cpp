#include "core/task/grasp_closing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace handlab::sim {

const std::vector<ClosingFactor>& closing_factors() {
  constexpr double kDegree = M_PI / 180.0;
  static const std::vector<ClosingFactor> factors = {
      {"over_closure", "mm", &GraspClosing::over_closure, 1e-3, {0, 3, 5, 10, 15, 20, 25, 30}},
      {"tilt_yaw", "deg", &GraspClosing::tilt_yaw, kDegree, {0, 10, 20, 30}},
      {"tilt_pitch", "deg", &GraspClosing::tilt_pitch, kDegree, {0, 10, 20, 30}},
      {"offset_along", "side", &GraspClosing::offset_along, 1.0, {0, 0.1, 0.2, 0.3, 0.4}},
      {"lead", "ms", &GraspClosing::lead_s, 1e-3, {-200, -100, 0, 50, 100, 150, 200}},
      {"closing_speed", "cm/s", &GraspClosing::closing_speed, 1e-2, {2, 5, 10, 20, 30}},
      {"hold", "s", &GraspClosing::hold_s, 1.0, {1, 5, 10}},
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
  const bool positive = f->name == "closing_speed" || f->name == "hold";
  if (!(value >= lo && value <= hi) || (positive && !(value > 0)))
    throw std::invalid_argument(name + " must be from " + std::to_string(int(lo)) + " to " +
                                std::to_string(int(hi)) + " " + f->unit + ", not " +
                                std::to_string(value));
  closing.*(f->field) = value * f->scale;
}

std::string describe(const GraspClosing& closing) {
  const GraspClosing standard;
  std::ostringstream text;
  for (const ClosingFactor& f : closing_factors()) {
    const double value = closing.*(f.field);
    if (value == standard.*(f.field)) continue;
    text << (text.tellp() > 0 ? ", " : "") << f.name << " " << value / f.scale << " " << f.unit;
  }
  return text.tellp() > 0 ? text.str() : "the scripted pinch";
}

}  // namespace handlab::sim
