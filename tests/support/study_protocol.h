// The study's protocol as the tests read it, and a protocol's text with one passage changed
// (a variant of a protocol, written out by a test).
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace handlab::test {

inline const std::string kStudy =
    std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021.json";

// `text` with the first `from` replaced by `to`; a test failure if there is no `from`.
inline std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace handlab::test
