#include "core/util/data_files.h"

#include <filesystem>

namespace handlab::util {

std::string installed_data_directory() {
  return HANDLAB_DATA_DIR;
}

std::string find_data_file(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path asked(path);
  if (path.empty() || std::filesystem::exists(asked, ec) || asked.is_absolute()) return path;
  const std::filesystem::path installed = std::filesystem::path(HANDLAB_DATA_DIR) / asked;
  return std::filesystem::exists(installed, ec) ? installed.string() : path;
}

}  // namespace handlab::util
