// Every output option of every command, pointed where users point outputs: /dev/null, a
// named pipe with a reader, standard output (-) and a symbolic link. Each writes through or
// follows, and none replaces what the path names.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::output_targets_test {
namespace {

using handlab::test::CliResult;
using handlab::test::file_bytes;
using handlab::test::fresh_path;
using handlab::test::run_cli;

const std::string kSource = HANDLAB_SOURCE_DIR;
const std::string kRecording = kSource + "/data/leap/pinch.json.lz";

// A command line with {OUT} where the output goes, and the name an output of its kind has
// (its extension chooses the format of some).
struct OutputUse {
  std::string command;
  std::string file_name;
};

// What the commands read: a small simulated study with frames, its export, a sensitivity
// analysis to draw again: made once for all the cases.
class OutputTargets : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    // A folder of this process' own: CTest runs each of these tests in a process, at once.
    dir_ = fresh_path("output-targets-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    protocol_ = dir_ + "/two-blocks.json";
    std::ofstream(protocol_) << handlab::test::with(file_bytes(handlab::test::kStudy),
                                                    "\"blocks\": 5", "\"blocks\": 2");
    db_ = dir_ + "/study.db";
    const CliResult made = run_cli("simulate --protocol " + protocol_ +
                                   " --participants 3 --seed 4 --world proxy --frames --quiet "
                                   "--jobs 2 --db " +
                                   db_);
    ASSERT_EQ(made.status, 0) << made.out;
    ASSERT_EQ(run_cli("export --db " + db_ + " --out " + dir_ + "/export").status, 0);
    const CliResult sensitivity =
        run_cli("sensitivity --protocol " + protocol_ + " --work " + dir_ +
                "/work --participants 2 --trajectories 2 --parameter fitts_a --jobs 2 --json " +
                dir_ + "/sensitivity.json");
    ASSERT_EQ(sensitivity.status, 0) << sensitivity.out;
  }

  static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }

  static std::vector<OutputUse> uses() {
    const std::string db = db_, p = protocol_, rec = kRecording;
    return {
        {"analyze --db " + db + " --json {OUT}", "analysis.json"},
        {"analyze --csv " + dir_ +
             "/export/trials.csv --subject participant --dv "
             "completion_time_s --within strategy,manipulation --json {OUT}",
         "analysis.json"},
        {"study status --db " + db + " --json {OUT}", "status.json"},
        {"grasps --db " + db + " --json {OUT}", "grasps.json"},
        {"merge --out {NEW} " + db + " --json {OUT}", "merged.json"},
        {"session run --db " + db + " --participant S01 --resume --json {OUT}", "session.json"},
        {"simulate --protocol " + p +
             " --participants 1 --seed 9 --world proxy --quiet --db "
             "{NEW} --json {OUT}",
         "simulated.json"},
        {"replications " + db + " --json {OUT}", "replications.json"},
        {"power --protocol " + p + " --pilot " + db + " --n 4 --sims 5 --quiet --json {OUT}",
         "power.json"},
        {"power --protocol " + p + " --pilot " + db + " --n 4 --sims 5 --quiet --plot {OUT}",
         "power.svg"},
        {"sensitivity --protocol " + p + " --from " + dir_ + "/sensitivity.json --json {OUT}",
         "sensitivity.json"},
        {"sensitivity --protocol " + p + " --from " + dir_ + "/sensitivity.json --plot {OUT}",
         "sensitivity.png"},
        {"sim pinch --cube 0.06 --json {OUT}", "pinch.json"},
        {"sim pinch --cube 0.06 --trace {OUT}", "trace.csv"},
        {"sim bench --duration 0.4 --threads 1 --runs 1 --steps {OUT}", "steps.csv"},
        {"sim grasp --cube 0.06 --jobs 1 --closing over_closure=3 --json {OUT}", "grasp.json"},
        {"sim settle --speed 0.5 --spin 0 --duration 0.1 --json {OUT}", "settle.json"},
        {"sim bench --duration 0.4 --threads 1 --runs 1 --json {OUT}", "bench.json"},
        {"sim replay " + rec + " --hold --duration 0.2 --json {OUT}", "replay.json"},
        {"retarget " + rec + " --json {OUT}", "retarget.json"},
        {"retarget " + rec + " --csv {OUT}", "errors.csv"},
        {"retarget " + rec + " --picture {OUT}", "pinch.png"},
        {"tracking info " + rec + " --json {OUT}", "info.json"},
        {"tracking convert " + rec + " --out {OUT}", "frames.csv"},
        {"hand --length 0.214 --json {OUT}", "hand.json"},
        {"hand --length 0.214 --out {OUT}", "skin.obj"},
        {"hand --length 0.214 --png {OUT}", "hand.png"},
        {"hand --length 0.214 --tets {OUT}", "flesh.vtk"},
        {"render --width 64 --height 48 --out {OUT}", "scene.png"},
    };
  }

  static CliResult run(const OutputUse& use, const std::string& out) {
    std::string command = use.command;
    command.replace(command.find("{OUT}"), 5, out);
    if (const auto at = command.find("{NEW}"); at != std::string::npos)
      command.replace(at, 5, dir_ + "/new-" + std::to_string(++made_) + ".db");
    return run_cli(command);
  }

  static std::string dir_, protocol_, db_;
  static int made_;
};

std::string OutputTargets::dir_, OutputTargets::protocol_, OutputTargets::db_;
int OutputTargets::made_ = 0;

std::string kind_of(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "missing";
  if (S_ISLNK(st.st_mode)) return "link";
  if (S_ISCHR(st.st_mode)) return "character device";
  if (S_ISFIFO(st.st_mode)) return "fifo";
  if (S_ISREG(st.st_mode)) return "file";
  return "other";
}

TEST_F(OutputTargets, DevNullIsWrittenThroughAndStaysTheDevice) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  for (const OutputUse& use : uses()) {
    const CliResult r = run(use, "/dev/null");
    EXPECT_EQ(r.status, 0) << use.command << "\n" << r.out;
    struct stat after {};
    ASSERT_EQ(::lstat("/dev/null", &after), 0);
    ASSERT_EQ(kind_of("/dev/null"), "character device") << use.command;
    EXPECT_EQ(after.st_rdev, before.st_rdev) << use.command;
  }
}

TEST_F(OutputTargets, ANamedPipeWithAReaderGetsTheOutput) {
  for (const OutputUse& use : uses()) {
    const std::string fifo = dir_ + "/fifo-" + use.file_name;
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto reader = std::async(std::launch::async, [&] { return file_bytes(fifo); });
    const CliResult r = run(use, fifo);
    // A command that failed before opening the pipe leaves the reader waiting: release it
    // (opening for writing fails until the reader has opened its end: try again).
    for (int k = 0;
         k < 100 && reader.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready;
         ++k) {
      const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
    }
    const std::string got = reader.get();
    EXPECT_EQ(r.status, 0) << use.command << "\n" << r.out;
    EXPECT_FALSE(got.empty()) << use.command;
    EXPECT_EQ(kind_of(fifo), "fifo") << use.command;
  }
}

TEST_F(OutputTargets, StandardOutputByDash) {
  for (const OutputUse& use : uses()) {
    const CliResult r = run(use, "-");
    EXPECT_EQ(r.status, 0) << use.command << "\n" << r.out;
    EXPECT_FALSE(r.out.empty()) << use.command;
    EXPECT_FALSE(std::filesystem::exists("-")) << use.command;
  }
}

TEST_F(OutputTargets, ASymbolicLinkIsFollowedToItsTargetAndStaysALink) {
  for (const OutputUse& use : uses()) {
    const std::string target = dir_ + "/target-" + use.file_name;
    const std::string link = dir_ + "/link-" + use.file_name;
    std::filesystem::remove(target);
    std::filesystem::remove(link);
    std::ofstream(target) << "old";
    std::filesystem::create_symlink(target, link);
    const CliResult r = run(use, link);
    EXPECT_EQ(r.status, 0) << use.command << "\n" << r.out;
    EXPECT_EQ(kind_of(link), "link") << use.command;
    EXPECT_EQ(kind_of(target), "file") << use.command;
    const std::string written = file_bytes(target);
    EXPECT_TRUE(!written.empty() && written != "old") << use.command;
  }
}

// The options that name a folder (export, report) write into the folder a link points to.
TEST_F(OutputTargets, AFolderNamedByALinkTakesTheFiles) {
  for (const std::string& command : {"export --frames --db " + db_, "report --db " + db_}) {
    const std::string target = dir_ + "/folder-target", link = dir_ + "/folder-link";
    std::filesystem::remove_all(target);
    std::filesystem::remove(link);
    std::filesystem::create_directories(target);
    std::filesystem::create_directory_symlink(target, link);
    const CliResult r = run_cli(command + " --out " + link);
    EXPECT_EQ(r.status, 0) << command << "\n" << r.out;
    EXPECT_EQ(kind_of(link), "link") << command;
    EXPECT_FALSE(std::filesystem::is_empty(target)) << command;
  }
}

}  // namespace
}  // namespace handlab::output_targets_test
