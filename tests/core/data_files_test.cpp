// Data files named as the docs name them (core/util/data_files.h): the source tree's where
// they exist, the installed package's otherwise (tests/package runs that side), and a name
// found nowhere comes back unchanged for the reader's error.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/util/data_files.h"

namespace handlab::util {
namespace {

TEST(DataFiles, AFileThatExistsIsItself) {
  const std::string protocol =
      std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021.json";
  EXPECT_EQ(find_data_file(protocol), protocol);
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(HANDLAB_SOURCE_DIR);
  EXPECT_EQ(find_data_file("data/leap/pinch.json.lz"), "data/leap/pinch.json.lz");
  std::filesystem::current_path(before);
}

TEST(DataFiles, ANameFoundNowhereComesBackUnchanged) {
  EXPECT_EQ(find_data_file("studies/no-such-protocol.json"), "studies/no-such-protocol.json");
  EXPECT_EQ(find_data_file("/no/such/file.json"), "/no/such/file.json");
  EXPECT_EQ(find_data_file(""), "");
}

TEST(DataFiles, ThePackagesFolderIsUnderShare) {
  EXPECT_TRUE(installed_data_directory().ends_with("/share/handlab")) << installed_data_directory();
}

}  // namespace
}  // namespace handlab::util
