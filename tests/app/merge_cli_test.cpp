// A simulated study run in shards (simulate --shard) and merged (merge) equals the study run
// in one process, export for export; each refusal of merge says which file and why and
// leaves every file as it was; a merge killed at any moment leaves no output and its inputs
// intact.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "core/store/sqlite_database.h"
#include "core/util/json_value.h"
#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/under_sanitizers.h"

namespace {

using handlab::test::file_bytes;
using handlab::test::fresh_path;
using Result = handlab::test::CliResult;
using handlab::test::run_cli;

using handlab::test::kStudy;

// The N = 4 proxy study of seed 11 with its frames, all of it or the shard `shard` ("K/M").
std::string simulate(const std::string& name, const std::string& shard = "",
                     const std::string& protocol = kStudy, int seed = 11, bool frames = true) {
  const std::string db = fresh_path(name);
  const Result r =
      run_cli("simulate --protocol " + protocol + " --participants 4 --seed " +
              std::to_string(seed) + " --world proxy --quiet --jobs 2 --db " + db +
              (frames ? " --frames" : "") + (shard.empty() ? "" : " --shard " + shard));
  EXPECT_EQ(r.status, 0) << r.out;
  return db;
}

// What a study gives a user: its exports and its analysis (the database's name and creation
// time left out: they are the file's, not the study's results).
struct Outputs {
  std::string trials, questionnaire, frames, analysis;
};
Outputs outputs(const std::string& db) {
  const std::string dir = fresh_path(std::filesystem::path(db).stem().string() + "-export");
  Result r = run_cli("export --db " + db + " --out " + dir + " --frames");
  EXPECT_EQ(r.status, 0) << r.out;
  r = run_cli("analyze --db " + db + " --json -");
  EXPECT_EQ(r.status, 0) << r.out;
  std::string analysis;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (line.find("\"db\":") == std::string::npos &&
        line.find("\"created_at\":") == std::string::npos)
      analysis += line + "\n";
  return {file_bytes(dir + "/trials.csv"), file_bytes(dir + "/questionnaire.csv"),
          file_bytes(dir + "/frames.csv"), analysis};
}

std::string merge(const std::string& name, const std::vector<std::string>& parts) {
  const std::string out = fresh_path(name);
  std::string args = "merge --out " + out;
  for (const std::string& p : parts) args += " " + p;
  const Result r = run_cli(args);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("4 participants from " + std::to_string(parts.size()) + " parts"),
            std::string::npos)
      << r.out;
  return out;
}

// The study's protocol with `blocks` blocks (and one practice trial per condition, or none),
// written to a fresh file.
std::string short_protocol(int blocks, bool practice_trials = false) {
  std::string text = file_bytes(kStudy);
  text.replace(text.find("\"blocks\": 5"), 11, "\"blocks\": " + std::to_string(blocks));
  if (practice_trials) text = handlab::test::with_practice(text);
  const std::string path = fresh_path("merge_protocol_" + std::to_string(blocks) +
                                      (practice_trials ? "_practice" : "") + ".json");
  std::ofstream(path) << text;
  return path;
}

TEST(CliMerge, ShardsMergedEqualTheStudyRunInOneProcess) {
  // Two blocks of the study's design with practice trials, to spare the test's time.
  const std::string protocol = short_protocol(2, true);
  const Outputs whole = outputs(simulate("merge_whole.db", "", protocol));
  ASSERT_GT(std::count(whole.frames.begin(), whole.frames.end(), '\n'), 10000);
  ASSERT_NE(whole.analysis.find("\"manipulation\""), std::string::npos) << whole.analysis;
  // Two and four shards (a single shard merged is a copy of its part: nothing to compare);
  // under the sanitizers four alone, whose merge goes through all the code two shards' does.
  for (int m : {2, 4}) {
    if (handlab::test::kUnderSanitizers && m == 2) continue;
    std::vector<std::string> parts;
    for (int k = m; k >= 1; --k)  // in reverse: the merge restores the enrolment order
      parts.push_back(simulate("merge_shard" + std::to_string(k) + "of" + std::to_string(m) + ".db",
                               std::to_string(k) + "/" + std::to_string(m), protocol));
    const Outputs merged = outputs(merge("merge_of" + std::to_string(m) + ".db", parts));
    EXPECT_EQ(merged.trials, whole.trials) << m << " shards";
    EXPECT_EQ(merged.questionnaire, whole.questionnaire) << m << " shards";
    EXPECT_EQ(merged.frames, whole.frames) << m << " shards";
    EXPECT_EQ(merged.analysis, whole.analysis) << m << " shards";
  }
  // --only runs the named participants; a shard holds no one else.
  const std::string only = fresh_path("merge_only.db");
  const Result r =
      run_cli("simulate --protocol " + protocol +
              " --participants 4 --seed 11 --world proxy --quiet --only S03 --db " + only);
  ASSERT_EQ(r.status, 0) << r.out;
  handlab::store::Database db(only, handlab::store::Database::Mode::kReadOnly);
  EXPECT_EQ(db.query_text("SELECT group_concat(id || ':' || enrolment) FROM participant"), "S03:2");
}

// A refusal: a non-zero exit and one line that says `what`.
void refused(const Result& e, const std::string& what) {
  EXPECT_NE(e.status, 0) << e.out;
  EXPECT_EQ(e.out.find('\n'), e.out.size() - 1) << e.out;
  EXPECT_NE(e.out.find(what), std::string::npos) << e.out;
}

TEST(CliMerge, RefusalsSayWhichFileAndWhyAndChangeNothing) {
  const std::string protocol = short_protocol(1);
  const std::string a = simulate("merge_a.db", "1/2", protocol, 11, false),
                    b = simulate("merge_b.db", "2/2", protocol, 11, false);
  // Another protocol (with practice trials), another population seed, a text file, a damaged
  // study.
  const std::string other = simulate("merge_other.db", "2/2", short_protocol(1, true), 11, false);
  const std::string reseeded = simulate("merge_reseeded.db", "1/2", protocol, 12, false);
  const std::string not_a_study = fresh_path("merge_not_a_study.db");
  std::ofstream(not_a_study) << "participant,age\nS01,27\n";
  const std::string damaged = fresh_path("merge_damaged.db");
  std::filesystem::copy_file(b, damaged);
  {
    // An index that no longer matches its table: the file opens, integrity_check fails.
    handlab::store::Database db(damaged, handlab::store::Database::Mode::kReadWrite);
    db.exec("PRAGMA writable_schema = ON");
    db.exec(
        "UPDATE sqlite_master SET sql = 'CREATE INDEX trial_by_planned ON trial(attempt)' "
        "WHERE name = 'trial_by_planned'");
    db.exec("PRAGMA journal_mode = DELETE");
  }
  // The same people of another participant model (--set): S01 twice, with different data.
  const std::string changed = fresh_path("merge_changed.db");
  ASSERT_EQ(run_cli("simulate --protocol " + protocol +
                    " --participants 4 --seed 11 --world proxy --quiet --shard 1/2 --set "
                    "fitts_a=0.7 --db " +
                    changed)
                .status,
            0);
  const std::vector<std::string> files = {a, b, other, reseeded, changed, not_a_study, damaged};
  std::vector<std::string> before;
  for (const std::string& f : files) before.push_back(file_bytes(f));

  const std::string out = fresh_path("merge_refused.db");
  refused(run_cli("merge --out " + out + " " + a + " " + other),
          other + " is a study of another protocol");
  refused(run_cli("merge --out " + out + " " + a + " " + reseeded),
          reseeded + " is a part of another study (4 planned participants, population seed 12; " +
              a + " has 4, population seed 11)");
  refused(run_cli("merge --out " + out + " " + a + " " + changed),
          "participant S01 is in " + a + " and " + changed + " with different data");
  refused(run_cli("merge --out " + out + " " + a + " " + not_a_study),
          not_a_study + " is not a study database (not an SQLite file)");
  refused(run_cli("merge --out " + out + " " + a + " " + damaged),
          damaged + " is damaged (cut short or overwritten; SQLite's integrity check: ");
  refused(run_cli("merge --out " + out + " " + a + " " + out + ".missing"),
          out + ".missing: no such file");
  refused(run_cli("merge --out " + a + " " + b), a + " exists");
  refused(run_cli("merge --out " + out), "name the study databases to merge");
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
  for (std::size_t i = 0; i < files.size(); ++i)
    EXPECT_TRUE(file_bytes(files[i]) == before[i]) << files[i] << " changed";
  // The same participant in two parts with the same data is taken once.
  const Result twice = run_cli("merge --out " + out + " " + a + " " + b + " " + a + " --json -");
  ASSERT_EQ(twice.status, 0) << twice.out;
  const auto json = handlab::util::JsonValue::parse(twice.out);
  EXPECT_EQ(json["participants"].as_number(), 4);
  EXPECT_EQ(json["duplicates"].as_number(), 2);
  EXPECT_EQ(json["renumbered"].as_bool(), false);
}

TEST(CliMerge, KilledAtAnyMomentLeavesNoOutputAndItsInputsIntact) {
  const std::string protocol = short_protocol(2);
  const std::string a = simulate("merge_kill_a.db", "1/2", protocol),
                    b = simulate("merge_kill_b.db", "2/2", protocol);
  const std::string a_bytes = file_bytes(a), b_bytes = file_bytes(b);
  const std::string out = fresh_path("merge_killed.db");
  std::mt19937 rng(43);
  std::uniform_int_distribution<int> delay_us(0, 600000);  // a merge of these takes 0.5-1 s
  int killed = 0;
  for (int attempt = 0; attempt < 6; ++attempt) {
    const pid_t pid = fork();
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      dup2(null, 1);
      dup2(null, 2);
      execl(HANDLAB_CLI, HANDLAB_CLI, "merge", "--out", out.c_str(), a.c_str(), b.c_str(),
            static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ::kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (!(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)) {
      // It finished before the signal: the whole study is there; start again.
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
      ASSERT_TRUE(std::filesystem::exists(out));
      std::filesystem::remove(out);
      continue;
    }
    ++killed;
    EXPECT_FALSE(std::filesystem::exists(out)) << "killed after " << attempt;
    EXPECT_TRUE(file_bytes(a) == a_bytes);
    EXPECT_TRUE(file_bytes(b) == b_bytes);
  }
  EXPECT_GE(killed, 3);
  // A merge after the killed ones replaces what they left and completes.
  const Result r = run_cli("merge --out " + out + " " + a + " " + b);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
  handlab::store::Database db(out, handlab::store::Database::Mode::kReadOnly);
  EXPECT_EQ(db.query_text("PRAGMA integrity_check"), "ok");
  EXPECT_EQ(db.query_text("SELECT count(*) FROM participant"), "4");
}

}  // namespace
