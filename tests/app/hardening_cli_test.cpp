// What a user does that must neither harm the machine, lose data nor give a wrong answer, as
// a new user tried it (issue #68's findings, each a test that failed before): a half-merged
// study that looks whole, a contrast whose direction depends on who ran first, an export the
// program cannot read back, a skip that prints SQLite's words, files left by a stopped run,
// refusals in the program's terms instead of the user's, surprising defaults.
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/store/sqlite_database.h"
#include "core/util/json_value.h"
#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::hardening_test {
namespace {

using handlab::test::CliResult;
using handlab::test::file_bytes;
using handlab::test::fresh_path;
using handlab::test::run_cli;
using handlab::util::JsonValue;

const std::string kSource = HANDLAB_SOURCE_DIR;
const std::string kStudy = handlab::test::kStudy;

bool has(const CliResult& r, const std::string& text) {
  return r.out.find(text) != std::string::npos;
}

// A refusal: a non-zero exit, one line that says `what`, and nothing of the program's inside.
void refused(const CliResult& r, const std::string& what) {
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_TRUE(has(r, what)) << "expected \"" << what << "\" in: " << r.out;
  for (const char* inside :
       {"terminate called", "filesystem error", "cannot prepare", "step:", "constraint failed"})
    EXPECT_FALSE(has(r, inside)) << r.out;
}

std::string two_blocks(const std::string& name) {
  const std::string path = fresh_path(name);
  std::ofstream(path) << handlab::test::with(file_bytes(kStudy), "\"blocks\": 5", "\"blocks\": 2");
  return path;
}

std::string simulated(const std::string& name, int participants, const std::string& extra = "") {
  const std::string db = fresh_path(name);
  const CliResult r = run_cli("simulate --protocol " + two_blocks(name + ".json") +
                              " --participants " + std::to_string(participants) +
                              " --seed 1 --world proxy --quiet --jobs 2 --db " + db + extra);
  EXPECT_EQ(r.status, 0) << r.out;
  return db;
}

std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// 1. A study merged from some of its shards is refused, or written as partial and said to be
// partial everywhere, and completed by merging the rest in.
TEST(Hardening, AStudyMergedFromSomeOfItsPartsIsRefusedOrSaysItIsPartial) {
  const std::string protocol = two_blocks("partial.json");
  std::vector<std::string> parts;
  for (int shard = 1; shard <= 4; ++shard) {
    parts.push_back(fresh_path("partial-shard-" + std::to_string(shard) + ".db"));
    ASSERT_EQ(run_cli("simulate --protocol " + protocol +
                      " --participants 4 --seed 1 --world proxy --quiet --shard " +
                      std::to_string(shard) + "/4 --db " + parts.back())
                  .status,
              0);
  }
  const std::string out = fresh_path("shards-merged.db");
  refused(run_cli("merge --out " + out + " " + parts[0]), "1 of 4 planned participants");
  EXPECT_FALSE(std::filesystem::exists(out));
  CliResult r = run_cli("merge --partial --out " + out + " " + parts[0]);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r, "1 participant from 1 part")) << r.out;
  EXPECT_TRUE(has(r,
                  "partial study: 1 of 4 planned participants (missing enrolment places 2, "
                  "3, 4)"))
      << r.out;
  r = run_cli("study status --db " + out);
  EXPECT_TRUE(has(r, "partial study: 1 of 4")) << r.out;
  r = run_cli("analyze --db " + out);
  EXPECT_TRUE(has(r, "Partial study: 1 of 4")) << r.out;
  const JsonValue json = JsonValue::parse(run_cli("analyze --db " + out + " --json -").out);
  EXPECT_TRUE(json["study"]["partial"].as_bool());
  EXPECT_EQ(json["study"]["missing_places"].size(), 3u);
  // A merge over it needs --update; then the rest come in and it is whole.
  refused(run_cli("merge --out " + out + " " + parts[1]), "exists");
  r = run_cli("merge --update --out " + out + " " + parts[1] + " " + parts[2] + " " + parts[3]);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r, "4 participants from 3 parts")) << r.out;
  EXPECT_FALSE(has(r, "partial")) << r.out;
  EXPECT_FALSE(has(run_cli("study status --db " + out), "partial"));
  r = run_cli("merge --update --out " + out + " " + parts[1]);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r, "nothing to merge")) << r.out;
  // Parts of another study (another size) are not parts of this one.
  const std::string other = fresh_path("partial-other.db");
  ASSERT_EQ(run_cli("simulate --protocol " + protocol +
                    " --participants 2 --seed 1 --world proxy --quiet --shard 1/2 --db " + other)
                .status,
            0);
  refused(run_cli("merge --partial --out " + fresh_path("partial-mixed.db") + " " + parts[0] + " " +
                  other),
          "a part of another study");
  // Nor are shards of another population (another --seed), though their people never clash.
  const std::string reseeded = fresh_path("partial-reseeded.db");
  ASSERT_EQ(run_cli("simulate --protocol " + protocol +
                    " --participants 4 --seed 2 --world proxy --quiet --shard 2/4 --db " + reseeded)
                .status,
            0);
  refused(run_cli("merge --partial --out " + fresh_path("partial-reseeded-merge.db") + " " +
                  parts[0] + " " + reseeded),
          "population seed 2; " + parts[0] + " has 4, population seed 1");
}

// 1 (Slurm's files): the series the issue tried, run by hand with bash: a partial merge is
// reported as partial, and the merge job merges again once the missing parts are there.
TEST(Hardening, ASeriesWithAPartialMergeIsUnfinishedUntilItsMergeJobRunsAgain) {
  const std::string dir = fresh_path("partial-series");
  const std::string protocol = kSource + "/studies/fine-manipulation-2021.json";
  ASSERT_EQ(run_cli("simulate --protocol " + protocol +
                    " --participants 4 --seed 1 --world proxy --slurm " + dir + " --dry-run")
                .status,
            0);
  auto bash = [&](const std::string& script, const std::string& index) {
    const std::string command =
        "cd " + dir + " && bash " + script + " " + index + " > /dev/null 2>&1";
    return std::system(command.c_str());
  };
  ASSERT_EQ(bash("array.sh", "1"), 0);
  const std::string merged = dir + "/study-n4-seed1.db";
  const std::string part = dir + "/parts/n4-seed1/shard-2-of-4.db";
  refused(run_cli("merge --out " + merged + " " + part), "1 of 4 planned participants");
  ASSERT_EQ(run_cli("merge --partial --out " + merged + " " + part).status, 0);
  CliResult status = run_cli("simulate --status " + dir);
  EXPECT_TRUE(has(status, "partial")) << status.out;
  EXPECT_TRUE(has(status, "unfinished array tasks: 0,2,3")) << status.out;
  for (const char* index : {"0", "2", "3"}) ASSERT_EQ(bash("array.sh", index), 0);
  ASSERT_EQ(bash("merge.sh", ""), 0);
  status = run_cli("simulate --status " + dir + " --json -");
  const JsonValue json = JsonValue::parse(status.out);
  EXPECT_TRUE(json["studies"][0]["merged"].as_bool()) << status.out;
  EXPECT_FALSE(json["studies"][0]["merged_partial"].as_bool()) << status.out;
  EXPECT_TRUE(has(run_cli("study status --db " + merged), "4 participants"));
}

// 1 and 5. A study left under its unfinished name by a stopped merge or creation is refused
// by every command that opens a study, saying what it is.
TEST(Hardening, AnUnfinishedStudyFileIsRefusedSayingWhatItIs) {
  const std::string db = simulated("unfinished.db", 2);
  const std::string partial = fresh_path("stopped.db.partial");
  const std::string creating = fresh_path("stopped.db.creating");
  std::filesystem::copy_file(db, partial);
  std::filesystem::copy_file(db, creating);
  for (const std::string& command : std::vector<std::string>{
           "analyze --db ", "study status --db ", "export --out " + fresh_path("x") + " --db "})
    refused(run_cli(command + partial), "unfinished merge");
  refused(run_cli("analyze --db " + creating), "creation was stopped");
  refused(run_cli("merge --out " + fresh_path("from-partial.db") + " " + partial),
          "unfinished merge");
}

// 2. The contrasts read in the protocol's order, whichever condition came first in the data.
TEST(Hardening, AContrastReadsTheSameWayWhoeverRanFirst) {
  const std::string db = simulated("order.db", 3);
  const std::string swapped = fresh_path("order-swapped.db");
  std::filesystem::copy_file(db, swapped);
  {
    // Participant 1's first trial becomes one of another manipulation level, and so on for
    // every participant: the same data, another order of first appearance.
    handlab::store::Database d(swapped, handlab::store::Database::Mode::kReadWrite);
    d.exec(
        "UPDATE planned_trial SET position = 100000 + (SELECT count(*) FROM planned_trial q "
        "WHERE q.participant_id = planned_trial.participant_id) - 1 - position");
    d.exec("UPDATE planned_trial SET position = position - 100000");
  }
  auto anova_and_contrasts = [](const std::string& study) {
    const JsonValue j = JsonValue::parse(run_cli("analyze --db " + study + " --json -").out);
    std::string text;
    for (const JsonValue& row : j["completion_time"]["posthoc"].as_array())
      text += row["effect"].as_string() + ": " + row["contrast"].as_string() + " " +
              std::to_string(row["t"].as_number()) + "\n";
    return text;
  };
  const std::string before = anova_and_contrasts(db), after = anova_and_contrasts(swapped);
  EXPECT_FALSE(before.empty());
  EXPECT_EQ(before, after);
  EXPECT_NE(before.find("naive"), std::string::npos) << before;
}

// 3. What export writes, analyze --csv reads: a skipped trial's NA is a missing observation,
// and the completion-time ANOVA is the one analyze --db gives.
TEST(Hardening, TheProgramReadsItsOwnExportWithSkippedTrials) {
  const std::string db = simulated("roundtrip.db", 3);
  ASSERT_EQ(run_cli("session redo --db " + db + " --participant S01 --trial 2 --reason x").status,
            0);
  CliResult r = run_cli("session skip --db " + db + " --participant S01 --trial 2 --reason x");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string out = fresh_path("roundtrip-export");
  ASSERT_EQ(run_cli("export --db " + db + " --out " + out).status, 0);
  EXPECT_NE(file_bytes(out + "/trials.csv").find(",NA"), std::string::npos);
  // 7. Times to the microsecond, the precision of a time counted in 1/120 s steps, never a
  // double's last digits (7.1499999999999995).
  EXPECT_FALSE(std::regex_search(file_bytes(out + "/trials.csv"), std::regex("\\.[0-9]{7,}")));
  r = run_cli("analyze --csv " + out +
              "/trials.csv --subject participant --dv completion_time_s --within "
              "strategy,manipulation --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const JsonValue from_csv = JsonValue::parse(r.out);
  const JsonValue from_db = JsonValue::parse(run_cli("analyze --db " + db + " --json -").out);
  bool warned = false;
  for (const JsonValue& w : from_csv["design"]["warnings"].as_array())
    warned = warned || w.as_string().find("1 row with no completion_time_s (NA)") == 0;
  EXPECT_TRUE(warned) << r.out;
  // The --db analysis has repetition as a third factor; the two-factor table is its own below.
  const CliResult two = run_cli("analyze --csv " + out +
                                "/trials.csv --subject participant --dv completion_time_s "
                                "--within strategy,manipulation,repetition --json -");
  ASSERT_EQ(two.status, 0) << two.out;
  const JsonValue three_factors = JsonValue::parse(two.out);
  const JsonValue& a = three_factors["anova"];
  const JsonValue& b = from_db["completion_time"]["anova"];
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i]["effect"].as_string(), b[i]["effect"].as_string());
    EXPECT_NEAR(a[i]["F"].as_number(), b[i]["F"].as_number(), 1e-9) << a[i]["effect"].as_string();
  }
}

// 4. Skip, redo and run in any order the docs allow, each refusal saying what to do.
TEST(Hardening, SessionStepsAreRefusedOnlyWithWhatToDo) {
  const std::string db = simulated("session-steps.db", 1);
  refused(run_cli("session skip --db " + db + " --participant S01 --trial 3 --reason x"),
          "has a result (completed");
  refused(run_cli("session skip --db " + db + " --participant S01 --trial 99 --reason x"),
          "has no trial 99");
  // A participant whose first trial is skipped before anything ran starts without --resume.
  const std::string fresh = fresh_path("session-steps-fresh.db");
  ASSERT_EQ(
      run_cli("study create --protocol " + two_blocks("steps.json") + " --db " + fresh).status, 0);
  ASSERT_EQ(run_cli("participant add --db " + fresh +
                    " --id P1 --age 30 --sex F --handedness right --hand-length 0.18 "
                    "--vr-experience some")
                .status,
            0);
  ASSERT_EQ(run_cli("session skip --db " + fresh + " --participant P1 --trial 1 --reason x").status,
            0);
  ASSERT_EQ(run_cli("session redo --db " + fresh + " --participant P1 --trial 1 --reason y").status,
            0);
  const CliResult r = run_cli("session run --db " + fresh + " --participant P1 --quiet");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r, "8 trials run in")) << r.out;
}

// 5. A failed export leaves no file behind; a damaged study says so in words.
TEST(Hardening, AFailedExportLeavesNothingAndADamagedStudySaysSo) {
  const std::string db = simulated("damaged.db", 2);
  const std::string damaged = fresh_path("damaged-copy.db");
  std::filesystem::copy_file(db, damaged);
  {
    // The middle half of the file overwritten: the pages of the schedule, the trials and the
    // answers, wherever a schema places them among the others (8 KB in the middle once fell on
    // an index and an empty table, which no analysis reads).
    std::fstream f(damaged, std::ios::in | std::ios::out | std::ios::binary);
    const std::size_t size = std::filesystem::file_size(damaged);
    f.seekp(std::streamoff(size / 4));
    const std::string garbage(size / 2, '\x5a');
    f.write(garbage.data(), std::streamsize(garbage.size()));
  }
  const std::string before = file_bytes(damaged);
  const std::string out = fresh_path("damaged-export");
  refused(run_cli("export --db " + damaged + " --out " + out), "damaged");
  if (std::filesystem::exists(out)) {  // what was written before the failure is whole
    for (const std::string& name : names_in(out)) EXPECT_EQ(name.find(".part"), std::string::npos);
  }
  refused(run_cli("analyze --db " + damaged), "damaged");
  refused(run_cli("merge --out " + fresh_path("damaged-merge.db") + " " + damaged), "damaged");
  EXPECT_EQ(file_bytes(damaged), before);
}

// 6. Refusals in the user's terms.
TEST(Hardening, RefusalsSpeakTheUsersLanguage) {
  const std::string db = simulated("words.db", 1);
  refused(run_cli("study create --protocol " + kStudy + " --db /no/such/folder/x.db"),
          "cannot create /no/such/folder/x.db: the folder /no/such/folder does not exist");
  EXPECT_FALSE(has(run_cli("study create --protocol " + kStudy + " --db /no/such/folder/x.db"),
                   "x.db.creating"));
  const std::string file = fresh_path("words-a-file");
  std::ofstream(file) << "x";
  refused(run_cli("export --db " + db + " --out " + file), "is a file, not a folder");
  refused(run_cli("session run --db " + db + " --participant S01 --tracker scripte"),
          "did you mean scripted?");
  refused(run_cli("simulate --protocol " + kStudy + " --world sfot --db " + fresh_path("w.db")),
          "--world must be proxy or soft, not 'sfot' (did you mean soft?)");
  refused(run_cli("analyze --db " + db + " --jsno -"), "did you mean --json?");
  const std::string mm = fresh_path("words-mm.json");
  std::ofstream(mm) << handlab::test::with(file_bytes(kStudy), "\"cube_size\": 0.06",
                                           "\"cube_size\": 60");
  refused(run_cli("study create --protocol " + mm + " --db " + fresh_path("mm.db")),
          "in metres, 60 mm is 0.06");
  EXPECT_FALSE(std::filesystem::exists(fresh_path("mm.db")));
}

// 7. One default world, named with its cost; progress into a log a line at a time; counts
// and times as people write them.
TEST(Hardening, DefaultsAreNamedAndAlikeAndOutputReadsWell) {
  for (const char* command : {"simulate", "power", "session run", "sensitivity"}) {
    const CliResult help = run_cli(std::string(command) + " --help");
    EXPECT_TRUE(has(help, "--world proxy|soft")) << command;
    EXPECT_TRUE(has(help, "(default proxy)")) << command << help.out;
  }
  const std::string db = fresh_path("defaults.db");
  const CliResult r = run_cli("simulate --protocol " + two_blocks("defaults.json") +
                              " --participants 3 --seed 1 --jobs 2 --db " + db);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find('\r'), std::string::npos) << "a carriage return in a log";
  EXPECT_TRUE(has(r, "participants 3/3")) << r.out;
  const CliResult power = run_cli("power --protocol " + two_blocks("defaults-power.json") +
                                  " --pilot " + db + " --n 4,6 --sims 5");
  ASSERT_EQ(power.status, 0) << power.out;
  EXPECT_EQ(power.out.find('\r'), std::string::npos) << "a carriage return in a log";
  const CliResult one = run_cli("merge --partial --out " + fresh_path("defaults-one.db") + " " +
                                simulated("defaults-one-part.db", 1));
  EXPECT_TRUE(has(one, "1 participant from 1 part into")) << one.out;
  const std::string session_db = simulated("defaults-session.db", 1);
  ASSERT_EQ(
      run_cli("session redo --db " + session_db + " --participant S01 --trial 1 --reason x").status,
      0);
  const CliResult session =
      run_cli("session run --db " + session_db + " --participant S01 --resume --quiet");
  EXPECT_TRUE(has(session, "S01: 1 trial run in ")) << session.out;
  const auto in = session.out.find(" run in ");
  ASSERT_NE(in, std::string::npos);
  const std::string seconds = session.out.substr(in + 8, session.out.find(" s;") - in - 8);
  EXPECT_EQ(seconds.size() - seconds.find('.'), 2u) << seconds << ": one decimal";
}

}  // namespace
}  // namespace handlab::hardening_test
