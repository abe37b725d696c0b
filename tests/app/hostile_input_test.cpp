// Hostile input, as users and broken disks make it: bad protocols, databases, recordings,
// CSVs and parts given to every command that reads them, and runs stopped midway. Each case
// ends in one line and an exit status, never a crash, and leaves every input as it was and no
// file of its own behind.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::hostile_input_test {
namespace {

using handlab::test::CliResult;
using handlab::test::file_bytes;
using handlab::test::fresh_path;
using handlab::test::run_cli;

const std::string kSource = HANDLAB_SOURCE_DIR;

// The inputs in a folder of their own, so that a file a command leaves beside one shows;
// what the commands are asked to write goes elsewhere.
std::string inputs_folder() {
  static const std::string dir = [] {
    const std::string d = fresh_path("hostile-inputs-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

std::string new_output() {
  static int made = 0;
  const std::string dir = fresh_path("hostile-outputs-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir + "/new-" + std::to_string(++made);
}

std::string written(const std::string& name, const std::string& bytes) {
  const std::string path = inputs_folder() + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string two_blocks() {
  return written("two-blocks.json", handlab::test::with(file_bytes(handlab::test::kStudy),
                                                        "\"blocks\": 5", "\"blocks\": 2"));
}

// A study to spoil in different ways: made once.
const std::string& good_study() {
  static const std::string db = [] {
    const std::string path = fresh_path("hostile-good-" + std::to_string(::getpid()) + ".db");
    const CliResult r =
        run_cli("simulate --protocol " + two_blocks() +
                " --participants 2 --seed 1 --world proxy --frames --quiet --db " + path);
    EXPECT_EQ(r.status, 0) << r.out;
    return path;
  }();
  return db;
}

// The study cut to `keep_bytes`, or with its schema's pages (after the first) overwritten.
// A study whose participant P1 has not started: a session reads its recording first.
std::string not_started_study() {
  const std::string db = inputs_folder() + "/not-started.db";
  if (!std::filesystem::exists(db)) {
    EXPECT_EQ(run_cli("study create --protocol " + two_blocks() + " --db " + db).status, 0);
    EXPECT_EQ(run_cli("participant add --db " + db +
                      " --id P1 --age 30 --sex F --handedness right --hand-length 0.18 "
                      "--vr-experience some")
                  .status,
              0);
  }
  return db;
}

std::string spoiled_study(const std::string& name, std::size_t keep_bytes, bool overwrite_schema) {
  std::string bytes = file_bytes(good_study());
  if (overwrite_schema)
    std::fill(bytes.begin() + 4096, bytes.begin() + 4096 + 16384, '\x5a');
  else
    bytes.resize(keep_bytes);
  return written(name, bytes);
}

struct Hostile {
  std::string what;  // the input, for the failure message
  std::string path;
};

// Runs each command on each input: one line, exit 1 or 2, the input unchanged, no stray file
// beside it.
void expect_refused_cleanly(const std::vector<Hostile>& inputs,
                            const std::vector<std::string>& commands) {
  for (const Hostile& input : inputs) {
    const bool is_file = std::filesystem::is_regular_file(input.path);
    const std::string before = is_file ? file_bytes(input.path) : "";
    const auto folder = std::filesystem::path(input.path).parent_path();
    const auto entries = [&] {
      return std::distance(std::filesystem::directory_iterator(folder),
                           std::filesystem::directory_iterator());
    };
    const auto files_before = entries();
    for (std::string command : commands) {
      command.replace(command.find("{IN}"), 4, input.path);
      if (const auto at = command.find("{NEW}"); at != std::string::npos)
        command.replace(at, 5, new_output());
      const CliResult r = run_cli(command);
      const std::string where = input.what + ": " + command + "\n" + r.out;
      EXPECT_TRUE(r.status == 1 || r.status == 2) << where;
      EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << where;
      EXPECT_EQ(r.out.find("terminate called"), std::string::npos) << where;
      if (is_file) {
        EXPECT_EQ(file_bytes(input.path), before) << where;
      }
      EXPECT_EQ(entries(), files_before) << where << "a file was left beside the input";
      for (const char* side : {"-wal", "-shm", ".partial", ".creating"})
        EXPECT_FALSE(std::filesystem::exists(input.path + side)) << where << side;
    }
  }
}

TEST(HostileInput, BadProtocols) {
  const std::string study = file_bytes(handlab::test::kStudy);
  const std::vector<Hostile> protocols = {
      {"an empty file", written("empty.json", "")},
      {"binary", written("binary.json", std::string("\x89PNG\r\n\x1a\n\0\0\xff", 11))},
      {"cut short", written("cut.json", study.substr(0, study.size() / 2))},
      {"an array", written("array.json", "[1, 2, 3]")},
      {"nested deeply", written("deep.json", std::string(200000, '['))},
      {"a huge number",
       written("huge.json", handlab::test::with(study, "\"blocks\": 5", "\"blocks\": 1e308"))},
      {"a negative size", written("negative.json", handlab::test::with(study, "0.06", "-0.06"))},
      {"no factors",
       written("nofactors.json", handlab::test::with(study, "\"factors\"", "\"factorz\""))},
      {"a folder", inputs_folder() + "/folder"},
      {"nothing there", inputs_folder() + "/missing.json"},
  };
  std::filesystem::create_directories(protocols[8].path);
  expect_refused_cleanly(protocols, {"study create --protocol {IN} --db {NEW}",
                                     "simulate --protocol {IN} --participants 1 --db {NEW}",
                                     "power --protocol {IN} --pilot " + good_study()});
}

TEST(HostileInput, BadDatabases) {
  const std::string not_handlab = inputs_folder() + "/other.sqlite";
  std::filesystem::remove(not_handlab);
  ASSERT_EQ(std::system(("sqlite3 " + not_handlab +
                         " 'CREATE TABLE t (x); INSERT INTO t "
                         "VALUES (1);'")
                            .c_str()),
            0);
  const std::string partial = inputs_folder() + "/stopped.db.partial";
  std::filesystem::copy_file(good_study(), partial,
                             std::filesystem::copy_options::overwrite_existing);
  const std::vector<Hostile> databases = {
      {"an empty file", written("empty.db", "")},
      {"text", written("text.db", "participant,time\nP1,3\n")},
      {"the first 4 kB of a study", spoiled_study("first-4k.db", 4096, false)},
      {"a study cut in half",
       spoiled_study("half.db", std::filesystem::file_size(good_study()) / 2, false)},
      {"a study overwritten after its first page", spoiled_study("overwritten.db", 0, true)},
      {"another program's SQLite file", not_handlab},
      {"an unfinished merge", partial},
      {"nothing there", inputs_folder() + "/missing.db"},
  };
  expect_refused_cleanly(
      databases, {"analyze --db {IN}", "study status --db {IN}", "export --db {IN} --out {NEW}",
                  "grasps --db {IN}", "merge --out {NEW} {IN}",
                  "session run --db {IN} --participant S01 --resume", "replications {IN}",
                  "render --db {IN} --participant S01 --trial 1 --out {NEW}.png"});
}

TEST(HostileInput, BadRecordings) {
  const std::string pinch = file_bytes(kSource + "/data/leap/pinch.json.lz");
  const std::vector<Hostile> recordings = {
      {"an empty file", written("empty.json.lz", "")},
      {"garbage", written("garbage.json.lz", std::string(5000, '\x01'))},
      {"cut short", written("cut.json.lz", pinch.substr(0, 60))},
      {"JSON of another shape", written("other.json", "{\"frames\": [{\"hands\": 7}]}")},
      {"a hlrec header alone", written("header.hlrec", "HLRC")},
  };
  expect_refused_cleanly(recordings, {"tracking info {IN}", "retarget {IN}", "sim replay {IN}",
                                      "tracking convert {IN} --out {NEW}.csv",
                                      "session run --db " + not_started_study() +
                                          " --participant P1 --resume --tracker {IN}"});
}

TEST(HostileInput, BadCsvs) {
  const std::vector<Hostile> tables = {
      {"an empty file", written("empty.csv", "")},
      {"a header alone", written("header.csv", "id,cond,y\n")},
      {"ragged rows", written("ragged.csv", "id,cond,y\nP1,a,1\nP1,b\nP2,a,2,9\n")},
      {"an open quote", written("quote.csv", "id,cond,y\nP1,\"a,1\n")},
      {"NA only", written("na.csv", "id,cond,y\nP1,a,NA\nP1,b,NA\nP2,a,NA\nP2,b,NA\n")},
      {"words for numbers", written("words.csv", "id,cond,y\nP1,a,one\nP1,b,2\n")},
      {"one level", written("one-level.csv", "id,cond,y\nP1,a,1\nP2,a,2\n")},
      {"binary", written("binary.csv", std::string("\0\0\0\xff\xfe", 5))},
  };
  expect_refused_cleanly(tables, {"analyze --csv {IN} --subject id --dv y --within cond",
                                  "analyze --csv {IN} --subject id --within cond "
                                  "--nonparametric y"});
}

// Runs `command` in its own process, stops it with SIGTERM after `ms`, and returns its exit
// status (or the signal as a negative number).
int stopped_after(const std::string& command, int ms) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + command + " >/dev/null 2>&1").c_str(), nullptr);
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  ::kill(child, SIGTERM);
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFSIGNALED(status) ? -WTERMSIG(status) : WEXITSTATUS(status);
}

// Merge, export, report and simulate stopped at moments through their work: no stray file,
// and an output that is there is whole.
TEST(HostileInput, StoppedMidwayLeavesNoStrayFile) {
  const std::string cli = HANDLAB_CLI;
  const bool with_report = run_cli("report --help").status == 0;
  for (int ms : {5, 20, 60, 150, 400}) {
    const std::string dir =
        fresh_path("hostile-stopped-" + std::to_string(::getpid()) + "-" + std::to_string(ms));
    std::filesystem::create_directories(dir);
    std::vector<std::string> commands = {
        cli + " merge --out " + dir + "/merged.db " + good_study(),
        cli + " export --frames --db " + good_study() + " --out " + dir + "/export",
        cli + " simulate --protocol " + two_blocks() +
            " --participants 4 --seed 2 --world proxy --quiet --jobs 2 --db " + dir + "/sim.db",
    };
    if (with_report)
      commands.push_back(cli + " report --db " + good_study() + " --out " + dir + "/report");
    for (const std::string& command : commands) stopped_after(command, ms);
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      EXPECT_EQ(name.find(".part"), std::string::npos) << e.path() << " after " << ms << " ms";
      EXPECT_EQ(name.find(".creating"), std::string::npos) << e.path();
    }
    if (std::filesystem::exists(dir + "/sim.db")) {  // there only when whole
      handlab::store::StudyStore simulated(dir + "/sim.db",
                                           handlab::store::StudyStore::Access::kReadOnly);
      EXPECT_EQ(simulated.participants().size(), 4u);
      for (const auto& p : simulated.participants())
        EXPECT_FALSE(simulated.next_trial(p.id).has_value()) << p.id << " after " << ms << " ms";
    }
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      for (const char* side : {"-wal", "-shm", "-journal"}) {  // only beside a whole database
        if (!name.ends_with(side)) continue;
        const std::string whole = e.path().string();
        EXPECT_TRUE(std::filesystem::exists(whole.substr(0, whole.size() - std::strlen(side))))
            << e.path();
      }
    }
    if (std::filesystem::exists(dir + "/merged.db")) {
      handlab::store::StudyStore merged(dir + "/merged.db",
                                        handlab::store::StudyStore::Access::kReadOnly);
      EXPECT_EQ(merged.participants().size(), 2u);
    }
    if (!HasFailure()) std::filesystem::remove_all(dir);
  }
}

}  // namespace
}  // namespace handlab::hostile_input_test
