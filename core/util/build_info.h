// What this build of handlab is: its version (one, in CMakeLists.txt's project()) and the
// commit it was built from, as --version prints them and a study database records them.
#pragma once

#include <string>

namespace handlab::util {

std::string program_version();  // "0.28.0"
std::string build_commit();     // a short hash, "-dirty" with uncommitted changes, or "unknown"
std::string version_line();     // "0.28.0 (commit 69c975b1a2b3)"

}  // namespace handlab::util
