// Writing a command's output to a file or, for "-", to standard output.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace handlab::cli {

// Writes through a temporary file renamed into place, so a failed run never leaves half a
// file; throws std::runtime_error naming the path.
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace handlab::cli
