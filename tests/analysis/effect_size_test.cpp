// Effect sizes and their noncentral intervals against R (tests/data/r/effect_size_reference.R:
// base R's pf and pt with ncp, and uniroot).
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "analysis/stats/effect_size.h"
#include "core/util/json_value.h"

namespace handlab::stats::effect_size_test {
namespace {

util::JsonValue reference() {
  std::ifstream in(std::string(HANDLAB_SOURCE_DIR) + "/tests/data/r/effect_size_reference.json");
  std::stringstream text;
  text << in.rdbuf();
  return util::JsonValue::parse(text.str());
}

TEST(EffectSize, PartialEtaSquaredAndItsNoncentralFIntervalAsR) {
  const util::JsonValue r = reference();
  ASSERT_EQ(r["F"].size(), 5u);
  for (const util::JsonValue& c : r["F"].as_array()) {
    const double f = c["F"].as_number(), df1 = c["df1"].as_number(), df2 = c["df2"].as_number();
    const std::string what =
        "F(" + c["df1"].dump() + ", " + c["df2"].dump() + ") = " + c["F"].dump();
    EXPECT_NEAR(partial_eta_squared(f, df1, df2), c["pes"].as_number(), 1e-14) << what;
    const EffectInterval ci = partial_eta_squared_interval(f, df1, df2);
    EXPECT_NEAR(ci.low, c["low"].as_number(), 1e-7) << what;
    EXPECT_NEAR(ci.high, c["high"].as_number(), 1e-7) << what;
  }
}

TEST(EffectSize, PairedDzAndItsNoncentralTIntervalAsR) {
  const util::JsonValue r = reference();
  ASSERT_EQ(r["t"].size(), 4u);
  for (const util::JsonValue& c : r["t"].as_array()) {
    const double t = c["t"].as_number(), df = c["df"].as_number();
    const std::string what = "t(" + c["df"].dump() + ") = " + c["t"].dump();
    EXPECT_NEAR(paired_dz(t, df + 1), c["dz"].as_number(), 1e-14) << what;
    const EffectInterval ci = paired_dz_interval(t, df, df + 1);
    EXPECT_NEAR(ci.low, c["low"].as_number(), 1e-6) << what;
    EXPECT_NEAR(ci.high, c["high"].as_number(), 1e-6) << what;
  }
}

// A value computed by hand: F(1, 19) = 8.78 explains 8.78 / (8.78 + 19) of its effect and
// error; t(19) = 3.52 is 3.52 / sqrt(20) standard deviations of the differences.
TEST(EffectSize, ByHand) {
  EXPECT_DOUBLE_EQ(partial_eta_squared(8.78, 1, 19), 8.78 / 27.78);
  EXPECT_DOUBLE_EQ(paired_dz(3.52, 20), 3.52 / std::sqrt(20.0));
  // An interval holds its estimate; a larger level holds the smaller one.
  const EffectInterval ci95 = paired_dz_interval(3.52, 19, 20),
                       ci80 = paired_dz_interval(3.52, 19, 20, 0.8);
  EXPECT_LT(ci95.low, ci80.low);
  EXPECT_GT(ci95.high, ci80.high);
  EXPECT_LT(ci80.low, paired_dz(3.52, 20));
}

}  // namespace
}  // namespace handlab::stats::effect_size_test
