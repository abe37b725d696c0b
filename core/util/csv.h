// Comma-separated values as RFC 4180 has them: fields with commas, quotes or line breaks
// quoted, quotes doubled; and numbers as people write them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace handlab::util {

// The field as written in a CSV file (quoted only when it has to be).
std::string csv_field(const std::string& text);

// The shortest text that reads back as the same double, without an exponent for the
// magnitudes of measured data (1e-5 up to 1e15): 60 is "60", 0.1 is "0.1", 1e-7 is "1e-07".
std::string format_number(double x);

// The rows of a CSV text: quoted fields may hold commas, doubled quotes and line breaks;
// lines end in LF or CRLF; a UTF-8 byte-order mark is skipped; a final line break does not
// make an empty row. Throws std::runtime_error on a quote left open.
std::vector<std::vector<std::string>> parse_csv(std::string_view text);

}  // namespace handlab::util
