// Files the tests write: a fresh path under the test directory, and a file's bytes (to
// check that a refused operation left a file exactly as it was).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace handlab::test {

// HANDLAB_TEST_TMP/name, with any earlier file of that name and its SQLite companions gone.
inline std::string fresh_path(const std::string& name) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/" + name;
  for (const char* side : {"", "-wal", "-shm", "-journal", ".creating", ".partial"})
    std::filesystem::remove_all(path + side);
  return path;
}

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace handlab::test
