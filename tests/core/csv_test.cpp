// CSV as RFC 4180 writes it, and numbers as people write them.
#include <gtest/gtest.h>

#include "core/util/csv.h"

namespace handlab::util {
namespace {

TEST(Csv, ReadsQuotedFieldsEmbeddedCommasQuotesAndLineBreaks) {
  const auto rows = parse_csv(
      "\xEF\xBB\xBFid,notes,time\r\nP01,\"left-handed, wears glasses\",12.5\r\n"
      "P02,\"said \"\"too small\"\"\",60\nP03,\"two\nlines\",\r\n");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"id", "notes", "time"}));
  EXPECT_EQ(rows[1][1], "left-handed, wears glasses");
  EXPECT_EQ(rows[2][1], "said \"too small\"");
  EXPECT_EQ(rows[2][2], "60");
  EXPECT_EQ(rows[3], (std::vector<std::string>{"P03", "two\nlines", ""}));
  EXPECT_THROW(parse_csv("a,\"open\n"), std::runtime_error);
  EXPECT_TRUE(parse_csv("").empty());
}

TEST(Csv, WritesFieldsThatReadBack) {
  const std::vector<std::string> fields = {"plain", "a,b", "say \"hi\"", "two\r\nlines", ""};
  std::string line;
  for (const auto& f : fields) line += (line.empty() ? "" : ",") + csv_field(f);
  const auto rows = parse_csv(line + "\r\n");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0], fields);
}

TEST(Csv, NumbersAsPeopleWriteThemAndReadBackExactly) {
  EXPECT_EQ(format_number(60.0), "60");
  EXPECT_EQ(format_number(100.0), "100");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(12.341666666666667), "12.341666666666667");
  EXPECT_EQ(format_number(0.214), "0.214");
  EXPECT_EQ(format_number(123456789.0), "123456789");
  EXPECT_EQ(format_number(-2500.0), "-2500");
  EXPECT_EQ(format_number(0.00012), "0.00012");
  EXPECT_EQ(format_number(1e-7), "1e-07");
  EXPECT_EQ(format_number(0.0), "0");
  for (double x : {60.0, 1.0 / 3.0, 2.0 / 3.0 * 1e4, 1e14 + 0.5, 0.00012345678901234, 7e-6})
    EXPECT_EQ(std::strtod(format_number(x).c_str(), nullptr), x) << format_number(x);
}

}  // namespace
}  // namespace handlab::util
