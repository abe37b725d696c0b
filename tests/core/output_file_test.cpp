// An output written where the user pointed it: a file replaced whole, a device or pipe
// written through, a link followed, anything else refused, and nothing left behind.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <future>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/util/output_file.h"
#include "core/util/temporary_files.h"
#include "tests/support/test_files.h"

namespace handlab::util::output_file_test {
namespace {

namespace fs = std::filesystem;

std::string fresh_folder(const std::string& name) {
  const std::string dir = test::fresh_path(name);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
  return st.st_mode;
}

TEST(OutputFile, ANewFileIsWrittenWholeAndAnOldOneReplacedKeepingItsPermissions) {
  const std::string dir = fresh_folder("output-regular");
  const std::string path = dir + "/out.json";
  write_output(path, [](std::ostream& out) { out << "first"; });
  EXPECT_EQ(test::file_bytes(path), "first");
  ::chmod(path.c_str(), 0640);
  write_output_bytes(path, "second");
  EXPECT_EQ(test::file_bytes(path), "second");
  EXPECT_EQ(mode_of(path) & 07777, 0640u);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"out.json"});
}

TEST(OutputFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const std::string dir = fresh_folder("output-failed");
  const std::string path = dir + "/trials.csv";
  write_output_bytes(path, "kept");
  EXPECT_THROW(write_output(path,
                            [](std::ostream& out) {
                              out << "half";
                              throw std::runtime_error("database disk image is malformed");
                            }),
               std::runtime_error);
  EXPECT_EQ(test::file_bytes(path), "kept");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"trials.csv"});
}

TEST(OutputFile, DevNullIsWrittenThroughAndStaysTheDevice) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  write_output("/dev/null", [](std::ostream& out) { out << "nothing"; });
  write_output_bytes("/dev/null", "nothing");
  struct stat after {};
  ASSERT_EQ(::lstat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_rdev, before.st_rdev);
  EXPECT_EQ(after.st_ino, before.st_ino);
}

TEST(OutputFile, ANamedPipeIsWrittenThroughToItsReader) {
  const std::string dir = fresh_folder("output-fifo");
  const std::string fifo = dir + "/pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return test::file_bytes(fifo); });
  std::string big(200000, 'x');  // more than a pipe's buffer: the reader must drain it
  write_output_bytes(fifo, big);
  EXPECT_EQ(reader.get(), big);
  EXPECT_TRUE(S_ISFIFO(mode_of(fifo)));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"pipe"});
}

TEST(OutputFile, ASymbolicLinkIsFollowedAndStaysALink) {
  const std::string dir = fresh_folder("output-link");
  fs::create_directories(dir + "/results");
  write_output_bytes(dir + "/results/real.json", "old");
  fs::create_symlink("results/real.json", dir + "/link.json");
  write_output_bytes(dir + "/link.json", "new");
  EXPECT_TRUE(S_ISLNK(mode_of(dir + "/link.json")));
  EXPECT_EQ(test::file_bytes(dir + "/results/real.json"), "new");
  // A link to a file not there yet makes the file; a link to /dev/null writes through.
  fs::create_symlink("results/later.json", dir + "/dangling.json");
  write_output_bytes(dir + "/dangling.json", "made");
  EXPECT_EQ(test::file_bytes(dir + "/results/later.json"), "made");
  fs::create_symlink("/dev/null", dir + "/null");
  write_output_bytes(dir + "/null", "gone");
  EXPECT_TRUE(S_ISCHR(mode_of("/dev/null")));
  EXPECT_EQ(names_in(dir + "/results"), (std::vector<std::string>{"later.json", "real.json"}));
}

TEST(OutputFile, StandardOutputByDashAndByItsDeviceName) {
  testing::internal::CaptureStdout();
  write_output_bytes("-", "dash ");
  write_output_bytes("/dev/stdout", "device");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "dash device");
}

TEST(OutputFile, AFolderAMissingFolderAndABlockDeviceAreRefusedWithTheReason) {
  const std::string dir = fresh_folder("output-refused");
  auto message = [](const std::string& path) {
    try {
      write_output_bytes(path, "x");
    } catch (const OutputError& e) {
      return std::string(e.what());
    }
    return std::string("written");
  };
  EXPECT_EQ(message(dir), "cannot write " + dir + ": it is a folder (name a file in it)");
  EXPECT_EQ(message(dir + "/no/such.json"),
            "cannot write " + dir + "/no/such.json: the folder " + dir + "/no does not exist");
  EXPECT_EQ(message(""), "cannot write to an empty path");
  fs::create_symlink("loop", dir + "/loop");
  EXPECT_NE(message(dir + "/loop").find("too many levels of symbolic links"), std::string::npos);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"loop"});
  for (const char* disk : {"/dev/loop0", "/dev/sda", "/dev/vda"}) {
    struct stat st {};
    if (::stat(disk, &st) != 0 || !S_ISBLK(st.st_mode)) continue;
    EXPECT_NE(message(disk).find("block device"), std::string::npos) << disk;
  }
}

TEST(OutputFile, ATemporaryIsRemovedWhenTheRunIsInterrupted) {
  const std::string dir = fresh_folder("output-interrupted");
  const std::string part = dir + "/study.db.partial";
  const pid_t child = ::fork();
  if (child == 0) {
    TemporaryFile temporary(part);
    ::close(::open(part.c_str(), O_WRONLY | O_CREAT, 0644));
    ::raise(SIGTERM);
    ::_exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_TRUE(names_in(dir).empty());
}

}  // namespace
}  // namespace handlab::util::output_file_test
