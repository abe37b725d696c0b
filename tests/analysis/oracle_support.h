// Comparing handlab's statistics with reference results computed in R (tests/data/oracle).
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/util/json_value.h"

namespace handlab::testing {

inline std::string oracle_path(const std::string& relative) {
  return std::string(HANDLAB_SOURCE_DIR) + "/tests/data/oracle/" + relative;
}

inline util::JsonValue read_json(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return util::JsonValue::parse(text.str());
}

// R writes NA, NaN and Inf as strings.
inline double r_number(const util::JsonValue& v) {
  if (v.is_number()) return v.as_number();
  if (v.is_string() && v.as_string() == "Inf") return INFINITY;
  if (v.is_string() && v.as_string() == "-Inf") return -INFINITY;
  return NAN;
}

enum class Tolerance { kValue, kP, kTukeyP };

// The acceptance tolerances: 1e-6 relative; p values below 1e-6 within 1e-10 absolute;
// Tukey p within 1e-9 absolute (R computes its upper tail as 1 - P).
inline void expect_r(double mine, const util::JsonValue& reference, const std::string& what,
                     Tolerance tolerance = Tolerance::kValue) {
  const double r = r_number(reference);
  if (std::isnan(r)) {
    EXPECT_TRUE(std::isnan(mine)) << what << ": R has NA/NaN, handlab " << mine;
    return;
  }
  double allowed = 1e-6 * std::abs(r);
  if (tolerance == Tolerance::kP && std::abs(r) < 1e-6) allowed = 1e-10;
  if (tolerance == Tolerance::kTukeyP) allowed = 1e-9;
  if (std::abs(r) < 1e-300 && tolerance == Tolerance::kValue) allowed = 1e-12;
  EXPECT_NEAR(mine, r, allowed) << what;
}

}  // namespace handlab::testing
