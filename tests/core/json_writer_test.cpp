// JSON as handlab writes it: what JsonValue reads back, 64-bit integers to their last digit,
// and the numbers JSON lacks as null.
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include <gtest/gtest.h>

#include "core/util/json_value.h"
#include "core/util/json_writer.h"

namespace handlab::util {
namespace {

TEST(JsonWriter, WritesWhatReadsBackEveryDigitOfA64BitSeedAndNullForNaN) {
  std::ostringstream out;
  JsonWriter w(out);
  const std::uint64_t seed = std::numeric_limits<std::uint64_t>::max();
  w.begin_object()
      .field("seed", seed)
      .field("negative", -3)
      .field("ratio", 0.1)
      .field("missing", std::nan(""))
      .field("text", "say \"hi\"\n")
      .key("list")
      .string_array({"a", "b"})
      .end_object();
  const std::string text = out.str();
  EXPECT_NE(text.find("\"seed\": 18446744073709551615"), std::string::npos) << text;
  const JsonValue j = JsonValue::parse(text);
  EXPECT_EQ(j["negative"].as_number(), -3.0);
  EXPECT_EQ(j["ratio"].as_number(), 0.1);
  EXPECT_TRUE(j["missing"].is_null());
  EXPECT_EQ(j["text"].as_string(), "say \"hi\"\n");
  EXPECT_EQ(j["list"][1].as_string(), "b");
}

}  // namespace
}  // namespace handlab::util
