// handlab-cli as a user calls it: exit status, one-line errors, the files it writes.
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/render/image.h"

namespace {

struct Result {
  int status;
  std::string out;
};

// Runs handlab-cli with the given arguments, capturing stdout and stderr together.
Result cli(const std::string& args) {
  const std::string command = std::string(HANDLAB_CLI) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    out.append(buffer.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

TEST(Cli, Version) {
  const Result r = cli("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("handlab-cli ", 0), 0u) << r.out;
}

TEST(Cli, HelpListsCommandsAndEachCommandHasHelp) {
  const Result r = cli("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("render"), std::string::npos);
  const Result h = cli("render --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.out.find("--width"), std::string::npos);
}

TEST(Cli, ErrorsAreOneLineWithNonZeroStatus) {
  for (const char* args : {"no-such-command", "render --width", "render --width abc",
                           "render --bogus 1", "render --out /no/such/dir/x.png"}) {
    const Result r = cli(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << args << ": " << r.out;
  }
}

TEST(Cli, RenderWritesThePicture) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/cli_scene.png";
  std::filesystem::remove(path);
  const Result r = cli("render --out " + path + " --width 320 --height 200");
  ASSERT_EQ(r.status, 0) << r.out;
  int w = 0, h = 0;
  ASSERT_TRUE(handlab::render::read_png_size(path, &w, &h));
  EXPECT_EQ(w, 320);
  EXPECT_EQ(h, 200);
}

}  // namespace
