// Radians in a degree: the hands' joint limits and rest angles are tabled in degrees, as the
// anatomy literature gives them, and turned into radians where they are read.
#pragma once

#include <numbers>

namespace handlab::hand {

inline constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace handlab::hand
