#include "core/util/build_info.h"

#include "handlab/commit.h"
#include "handlab/version.h"

namespace handlab::util {

std::string program_version() {
  return HANDLAB_VERSION;
}

std::string build_commit() {
  return HANDLAB_COMMIT;
}

std::string version_line() {
  return program_version() + " (commit " + build_commit() + ")";
}

}  // namespace handlab::util
