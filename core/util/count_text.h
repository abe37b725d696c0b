// A count with its noun, singular or plural as English has it: "1 participant", "4 participants".
#pragma once

#include <string>

namespace handlab::util {

inline std::string count_text(long long n, const std::string& noun,
                              const std::string& plural = {}) {
  return std::to_string(n) + " " + (n == 1 ? noun : plural.empty() ? noun + "s" : plural);
}

}  // namespace handlab::util
