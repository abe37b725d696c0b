// The study commands as an experimenter runs them, bad inputs, and the crash test: a session
// killed with SIGKILL at random moments loses no completed trial and resumes in order.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "core/render/image.h"
#include "core/store/sqlite_database.h"
#include "core/util/csv.h"
#include "core/util/json_value.h"
#include "tests/support/cli_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/under_sanitizers.h"

namespace {

using handlab::store::Database;
using handlab::store::Statement;

using Result = handlab::test::CliResult;
using handlab::test::run_cli;

using handlab::test::kStudy;

std::string enrol(const std::string& db, const std::string& id, double length) {
  return "participant add --db " + db + " --id " + id + " --age 27 --sex M --handedness right " +
         "--hand-length " + std::to_string(length) + " --vr-experience some";
}

// The study's protocol with two blocks, written to a fresh file.
std::string two_block_protocol(const std::string& name) {
  std::string protocol = handlab::test::file_bytes(kStudy);
  protocol.replace(protocol.find("\"blocks\": 5"), 11, "\"blocks\": 2");
  const std::string path = handlab::test::fresh_path(name);
  std::ofstream(path) << protocol;
  return path;
}

// A refusal: a non-zero exit and one line that says `what`.
void one_line_error(const Result& e, const std::string& what) {
  EXPECT_NE(e.status, 0) << e.out;
  EXPECT_EQ(e.out.find('\n'), e.out.size() - 1) << e.out;
  EXPECT_NE(e.out.find(what), std::string::npos) << e.out;
}

TEST(CliStudy, CreateEnrolRunStatusExportAnalyze) {
  const std::string db = handlab::test::fresh_path("cli_study.db");
  Result r =
      run_cli("study create --protocol " + handlab::test::study_with_practice() + " --db " + db);
  ASSERT_EQ(r.status, 0) << r.out;
  for (auto [id, length] :
       {std::pair{"P01", 0.17}, std::pair{"P02", 0.19}, std::pair{"P03", 0.2}}) {
    r = run_cli(enrol(db, id, length));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("24 trials planned"), std::string::npos) << r.out;
  }
  r = run_cli("study status --db " + db + " --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  {
    const auto status = handlab::util::JsonValue::parse(r.out);
    ASSERT_EQ(status["participants"].size(), 3u);
    EXPECT_EQ(status["participants"][0]["trials_planned"].as_number(), 24);
    EXPECT_EQ(status["participants"][0]["trials_completed"].as_number(), 0);
    EXPECT_EQ(status["participants"][0]["next"]["trial"].as_number(), 1);
  }
  for (const char* id : {"P01", "P02", "P03"}) {
    r = run_cli("session run --db " + db + " --participant " + id + " --tracker scripted --quiet");
    ASSERT_EQ(r.status, 0) << r.out;
  }
  r = run_cli("session run --db " + db + " --participant P01 --tracker scripted");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("--resume"), std::string::npos) << r.out;
  r = run_cli("study status --db " + db + " --json -");
  {
    const auto status = handlab::util::JsonValue::parse(r.out);
    for (const auto& p : status["participants"].as_array()) {
      EXPECT_EQ(p["trials_completed"].as_number(), 24);
      EXPECT_EQ(p["trials_aborted"].as_number(), 0);
      EXPECT_TRUE(p["next"].is_null());
    }
  }
  const std::string out = handlab::test::fresh_path("cli_export");
  r = run_cli("export --db " + db + " --out " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream trials(out + "/trials.csv");
  std::string header;
  std::getline(trials, header);
  EXPECT_EQ(header,
            "participant,age,sex,handedness,hand_length,vr_experience,block,order,strategy,"
            "manipulation,repetition,completion_time_s,outcome,grasps,drops,attempt");
  int rows = 0;
  for (std::string line; std::getline(trials, line);) ++rows;
  EXPECT_EQ(rows, 3 * 20) << "practice trials stay out";
  std::ifstream questionnaire(out + "/questionnaire.csv");
  std::getline(questionnaire, header);
  EXPECT_NE(header.find("repetition,precision,ease,naturalness"), std::string::npos) << header;

  // The frame log of the same trials: one row a logged step, the trial's columns on each.
  r = run_cli("export --db " + db + " --out " + out + " --frames");
  ASSERT_EQ(r.status, 0) << r.out;
  {
    const auto rows = handlab::util::parse_csv(handlab::test::file_bytes(out + "/frames.csv"));
    ASSERT_FALSE(rows.empty());
    const std::vector<std::string>& head = rows.front();
    auto column = [&](const std::string& name) {
      return std::size_t(std::find(head.begin(), head.end(), name) - head.begin());
    };
    ASSERT_EQ(head.size(), 28u);
    ASSERT_EQ(head.back(), "tracked_aperture");
    Database logged(db, Database::Mode::kReadOnly);
    EXPECT_EQ(std::to_string(rows.size() - 1),
              logged.query_text("SELECT count(*) FROM frame f JOIN trial t ON t.id = f.trial_id "
                                "JOIN planned_trial p ON p.id = t.planned_id WHERE p.practice = 0 "
                                "AND t.status IN ('completed', 'timeout')"));
    // P01's first exported trial, a success: its last step has the cube resting in B, the
    // task done; every step has its fingertips and the tracked hand's aperture.
    std::size_t last = 1;
    while (last + 1 < rows.size() && rows[last + 1][column("order")] == rows[1][column("order")] &&
           rows[last + 1][column("block")] == rows[1][column("block")])
      ++last;
    EXPECT_EQ(rows[1][column("participant")], "P01");
    if (rows[last][column("outcome")] == "success") {
      EXPECT_EQ(rows[last][column("phase")], "done");
      EXPECT_NEAR(std::stod(rows[last][column("cube_x")]), 0.15, 0.05) << "in zone B";
    }
    for (std::size_t k = 1; k <= last; ++k) {
      const double aperture = std::stod(rows[k][column("aperture")]);
      EXPECT_GT(aperture, 0.005);
      EXPECT_LT(aperture, 0.25);
      EXPECT_NE(rows[k][column("tracked_aperture")], "NA");
    }
  }

  r = run_cli("analyze --db " + db + " --json " + out + "/analysis.json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("strategy:manipulation"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Friedman"), std::string::npos);
  std::ifstream json(out + "/analysis.json");
  std::ostringstream text;
  text << json.rdbuf();
  const auto analysis = handlab::util::JsonValue::parse(text.str());
  EXPECT_TRUE(analysis.find("completion_time"));
  EXPECT_TRUE(analysis.find("questionnaire"));

  // Redo and skip, with reasons kept.
  r = run_cli("session redo --db " + db + " --participant P02 --trial 7 --reason 'tracking lost'");
  ASSERT_EQ(r.status, 0) << r.out;
  r = run_cli("study status --db " + db + " --json -");
  EXPECT_EQ(handlab::util::JsonValue::parse(r.out)["participants"][1]["next"]["trial"].as_number(),
            7);
  r = run_cli("session skip --db " + db +
              " --participant P02 --trial 7 --reason 'participant tired'");
  ASSERT_EQ(r.status, 0) << r.out;
  Database check(db, Database::Mode::kReadOnly);
  EXPECT_EQ(check.query_text("SELECT group_concat(status || ':' || reason) FROM trial WHERE reason "
                             "IS NOT NULL"),
            "redone:tracking lost,skipped:participant tired");

  // How each grasp met the cube, from the same frame logs: every grasp the task counted in the
  // trials with a result and frames (practice included; P02's redone trial 7 left out, its
  // skip without frames), each placed, dropped, landed, caught in the air or unfinished.
  r = run_cli("grasps --db " + db + " --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  {
    const auto grasps = handlab::util::JsonValue::parse(r.out);
    const std::string results =
        "FROM trial t WHERE t.status IN ('completed', 'timeout') AND t.frames > 0";
    EXPECT_EQ(std::to_string(int(grasps["trials"].as_number())),
              check.query_text("SELECT count(*) " + results));
    EXPECT_EQ(std::to_string(grasps["grasps"].size()),
              check.query_text("SELECT coalesce(sum(t.grasps), 0) " + results));
    int dropped = 0, placed = 0, by_thumb = 0;
    for (const auto& g : grasps["grasps"].as_array()) {
      dropped += g["outcome"].as_string() == "dropped";
      placed += g["outcome"].as_string() == "placed";
      EXPECT_TRUE(g["thumb"].as_string() == "tip" || g["thumb"].as_string() == "pad" ||
                  g["thumb"].as_string() == "base");
      EXPECT_LT(std::abs(g["pinch_offset_m"][1].as_number()),
                g["cube_size_m"].as_number() / 2 + 0.015)
          << "the pinch is on the cube, up and down";
      // Its closing in the grasp map's terms: each pad within 4 cm of its face while it held
      // the cube, their midpoint within a side of the cube's centre along the faces.
      for (const char* factor :
           {"over_closure", "tilt_yaw", "tilt_pitch", "offset_along", "lead", "closing_speed"})
        EXPECT_NE(g["closing"].find(factor), nullptr) << factor;
      EXPECT_LT(std::abs(g["closing"]["over_closure"].as_number()), 40.0);
      EXPECT_LT(g["closing"]["offset_along"].as_number(), 1.0);
    }
    EXPECT_EQ(std::to_string(dropped),
              check.query_text("SELECT coalesce(sum(t.drops), 0) " + results));
    EXPECT_EQ(std::to_string(placed),
              check.query_text("SELECT count(*) FROM trial WHERE status = 'completed'"));
    ASSERT_EQ(grasps["groups"].size(), 2u) << "the two cubes";
    for (const auto& group : grasps["groups"].as_array()) {
      for (const char* part : {"base", "pad", "tip"})
        by_thumb += int(group["by_thumb"][part]["grasps"].as_number());
      EXPECT_EQ(group["by_pinch_offset"].size(), 3u);
      // A tracked hand jitters: some of what a 0.1 s average leaves, under a centimetre.
      EXPECT_GT(group["jitter"]["root_rms_mm"]["median"].as_number(), 0.0);
      EXPECT_LT(group["jitter"]["root_rms_mm"]["median"].as_number(), 10.0);
      EXPECT_EQ(group["closings"]["kept"]["over_closure"]["unit"].as_string(), "mm");
    }
    EXPECT_EQ(by_thumb, int(grasps["grasps"].size()));
  }
  r = run_cli("grasps --db " + db + " --participant P01 --by condition");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("naive-fine"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lost, by the part of the distal phalanx"), std::string::npos) << r.out;
  EXPECT_EQ(run_cli("grasps --db " + db + " --by hand").status, 2);
  r = run_cli("grasps --db " + db + " --participant P09");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("no participant 'P09'"), std::string::npos) << r.out;

  // A moment of a stored trial, drawn from the frame log: P02's trial 7, redone then skipped,
  // keeps the frames of its first attempt.
  const std::string png = out + "/moment.png";
  r = run_cli("render --db " + db +
              " --participant P02 --trial 7 --time 1.504 --width 320 --height " + "200 --out " +
              png);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("P02 trial 7 (attempt 1, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(") at 1.50 s of "), std::string::npos) << r.out;
  int width = 0, height = 0;
  ASSERT_TRUE(handlab::render::read_png_size(png, &width, &height));
  EXPECT_EQ(width, 320);
  EXPECT_EQ(height, 200);
  for (const auto& [args, error] :
       {std::pair{"--participant P02 --trial 99", "P02 has no trial 99 (the schedule has 24)"},
        std::pair{"--participant P02 --trial 7 --attempt 3", "trial 7 of P02 has no attempt 3"},
        std::pair{"--participant P02", "--db needs --participant and --trial"}}) {
    r = run_cli("render --db " + db + " " + args + " --out " + png);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.out.find(error), std::string::npos) << r.out;
  }
}

// A simulated study from the command line (one block, on the grasp proxy: quick): the
// outcome per condition in JSON, the participants enrolled as simulated, bad options refused.
TEST(CliSimulate, RunsAStudyAndReportsEveryConditionsOutcome) {
  std::string protocol = handlab::test::file_bytes(kStudy);
  protocol.replace(protocol.find("\"blocks\": 5"), 11, "\"blocks\": 1");
  const std::string one_block = handlab::test::fresh_path("cli_one_block.json");
  std::ofstream(one_block) << protocol;
  const std::string db = handlab::test::fresh_path("cli_simulated.db");
  Result r = run_cli("simulate --protocol " + one_block + " --participants 2 --seed 3 --db " + db +
                     " --jobs 2 --world proxy --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = handlab::util::JsonValue::parse(r.out);
  EXPECT_EQ(doc["participants"].as_number(), 2);
  EXPECT_EQ(doc["trials"].as_number(), 2 * 4);  // one block of four each
  ASSERT_EQ(doc["conditions"].as_array().size(), 4u);
  for (const auto& c : doc["conditions"].as_array()) {
    EXPECT_EQ(c["trials"].as_number(), 2);
    EXPECT_EQ(c["completed"].as_number() + c["timeouts"].as_number() + c["skipped"].as_number(), 2);
    EXPECT_GE(c["success_rate"].as_number(), 0.0);
    EXPECT_LE(c["success_rate"].as_number(), 1.0);
  }
  // Where the participants' time went, a record per cube seen, never per condition.
  const auto& time = doc["participant_time"].as_array();
  ASSERT_EQ(time.size(), 2u);
  for (const auto& t : time) {
    EXPECT_EQ(t["trials"].as_number(), 4);
    EXPECT_GT(t["seconds"]["reach"].as_number(), 0.0);
    EXPECT_GE(t["missed_closings"].as_number(), 0.0);
    EXPECT_GE(t["slips"].as_number(), 0.0);
  }
  EXPECT_EQ(time[0]["cube_m"].as_number(), 0.01);
  EXPECT_EQ(time[1]["cube_m"].as_number(), 0.06);
  r = run_cli("study status --db " + db + " --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("S01"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("S02"), std::string::npos) << r.out;

  const std::string before = handlab::test::file_bytes(db);
  one_line_error(run_cli("simulate --protocol " + one_block + " --participants 1 --db " + db),
                 "exists");
  EXPECT_EQ(handlab::test::file_bytes(db), before);
  one_line_error(run_cli("simulate --protocol " + one_block + " --db " +
                         handlab::test::fresh_path("cli_rigid.db") + " --world rigid"),
                 "--world must be proxy or soft");
  one_line_error(run_cli("simulate --protocol " + one_block + " --participants 0 --db " +
                         handlab::test::fresh_path("cli_none.db")),
                 "--participants");
}

// Studies side by side as a script runs them: Markdown for people, JSON for programs, the
// published values matched, and one clear line for what cannot be summarised.
TEST(CliReplications, SetsStudiesSideBySideBesideThePublishedValues) {
  const std::string db = handlab::test::fresh_path("cli_replications.db");
  std::filesystem::copy_file(
      std::string(HANDLAB_SOURCE_DIR) + "/tests/data/studies/simulated-n20-seed1.db", db);
  const std::string published =
      std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021-published.json";
  const std::string copy = handlab::test::fresh_path("cli_replications_copy.db");
  std::filesystem::copy_file(db, copy);
  Result r = run_cli("replications " + db + " " + copy + " --published " + published);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("| strategy:manipulation | F | 8.78 (.008) | 8.74 (.008) | 8.74 (.008) | "
                       "8.74 | 8.74 to 8.74 | .008 | 2 of 2 | 2 of 2 |"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("| ours-fine | 98 % | 98 % | 98.0 % | 98–98 % |"), std::string::npos)
      << r.out;
  r = run_cli("replications " + db + " --published " + published +
              " --test strategy:manipulation --test \"precision (Friedman)\" --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = handlab::util::JsonValue::parse(r.out);
  EXPECT_EQ(doc["protocol"].as_string(), "fine-manipulation-2021");
  ASSERT_EQ(doc["studies"].size(), 1u);
  EXPECT_EQ(doc["studies"][0]["conditions"][1]["condition"].as_string(), "naive-fine");
  EXPECT_EQ(doc["studies"][0]["conditions"][1]["success_rate"].as_number(), 0.78);
  ASSERT_EQ(doc["tests"].size(), 2u);
  EXPECT_EQ(doc["tests"][1]["test"].as_string(), "precision (Friedman)");
  EXPECT_EQ(doc["tests"][1]["statistic"].as_string(), "chi2");
  EXPECT_EQ(doc["tests"][0]["published"]["value"].as_number(), 8.78);
  EXPECT_EQ(doc["tests"][0]["below_published"].as_number(), 1);  // 8.74 of the one study
  EXPECT_EQ(doc["tests"][0]["rejected"].as_number(), 1);
  one_line_error(run_cli("replications"), "give one or more study databases");
  one_line_error(run_cli("replications " + db + " " + db), "given twice");
  one_line_error(run_cli("replications " + db +
                         " --test \"strategy:manipulation: ours fine - naive "
                         "fine\""),
                 "no study made the test");
  one_line_error(run_cli("replications " + db + " --alpha 2"), "--alpha");
  one_line_error(run_cli("replications " + db + " --published " + kStudy), "handlab-published");
}

TEST(CliStudy, BadInputIsOneClearLineAndLeavesTheFileAlone) {
  const std::string db = handlab::test::fresh_path("cli_bad.db");
  ASSERT_EQ(run_cli("study create --protocol " + kStudy + " --db " + db).status, 0);
  ASSERT_EQ(run_cli(enrol(db, "P01", 0.18)).status, 0);
  const std::string before = handlab::test::file_bytes(db);
  one_line_error(run_cli(enrol(db, "P01", 0.18)), "already enrolled");
  one_line_error(run_cli("study create --protocol " + kStudy + " --db " + db), "already exists");
  one_line_error(run_cli("participant add --db " + db +
                         " --id P09 --age 27 --sex M --handedness right "
                         "--hand-length 18.8 --vr-experience some"),
                 "metres");
  EXPECT_EQ(handlab::test::file_bytes(db), before);

  // A protocol with an unknown factor: no database is created.
  std::string protocol = handlab::test::file_bytes(kStudy);
  protocol.replace(protocol.find("\"manipulation\""), 14, "\"glove\"");
  const std::string bad_protocol = handlab::test::fresh_path("cli_bad_protocol.json");
  std::ofstream(bad_protocol) << protocol;
  const std::string never = handlab::test::fresh_path("cli_never.db");
  one_line_error(run_cli("study create --protocol " + bad_protocol + " --db " + never),
                 "unknown factor");
  EXPECT_FALSE(std::filesystem::exists(never));

  // Newer, corrupt, truncated and locked files.
  const std::string newer = handlab::test::fresh_path("cli_newer.db");
  std::filesystem::copy_file(db, newer);
  { Database(newer, Database::Mode::kReadWrite).exec("PRAGMA user_version = 8"); }
  const std::string newer_bytes = handlab::test::file_bytes(newer);
  one_line_error(run_cli("study status --db " + newer), "newer handlab");
  one_line_error(run_cli("session run --db " + newer + " --participant P01"), "newer handlab");
  one_line_error(run_cli("session run --db " + newer + " --participant P01 --world rigid"),
                 "--world must be proxy or soft");
  EXPECT_EQ(handlab::test::file_bytes(newer), newer_bytes);

  const std::string corrupt = handlab::test::fresh_path("cli_corrupt.db");
  std::string garbage = before;
  for (std::size_t k = 100; k < garbage.size(); k += 7) garbage[k] = char(garbage[k] ^ 0x5a);
  std::ofstream(corrupt, std::ios::binary) << garbage;
  one_line_error(run_cli("study status --db " + corrupt), "cli_corrupt.db");
  one_line_error(run_cli(enrol(corrupt, "P02", 0.18)), "cli_corrupt.db");
  EXPECT_EQ(handlab::test::file_bytes(corrupt), garbage);

  const std::string truncated = handlab::test::fresh_path("cli_truncated.db");
  std::ofstream(truncated, std::ios::binary) << before.substr(0, before.size() / 2);
  const std::string cut = handlab::test::file_bytes(truncated);
  const Result t = run_cli("session run --db " + truncated + " --participant P01 --quiet");
  one_line_error(t, "cli_truncated.db");
  EXPECT_EQ(handlab::test::file_bytes(truncated), cut);

  {
    Database holder(db, Database::Mode::kReadWrite);
    holder.exec("PRAGMA locking_mode = EXCLUSIVE; BEGIN EXCLUSIVE");
    one_line_error(run_cli(enrol(db, "P02", 0.18)), "locked");
    holder.exec("ROLLBACK");
  }
  one_line_error(run_cli("study status --db " + handlab::test::fresh_path("cli_absent.db")),
                 "no study database");
  EXPECT_FALSE(std::filesystem::exists(std::string(HANDLAB_TEST_TMP) + "/cli_absent.db"));
}

struct Result_ {
  std::int64_t planned_id;
  int position;
  std::string status;
  double time;
};

// Every result (completed or timed out) of a participant, by trial id.
std::map<std::int64_t, Result_> results_of(Database& db, const std::string& id) {
  std::map<std::int64_t, Result_> out;
  Statement s = db.prepare(
      "SELECT t.id, t.planned_id, p.position, t.status, t.completion_time_s FROM trial t JOIN "
      "planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ? AND t.status IN "
      "('completed', 'timeout') ORDER BY t.id");
  s.bind(1, id);
  while (s.step())
    out[s.column_int64(0)] = {s.column_int64(1), int(s.column_int64(2)), s.column_text(3),
                              s.column_double(4)};
  return out;
}

pid_t spawn_session(const std::string& db, const std::string& id) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(HANDLAB_CLI, HANDLAB_CLI, "session", "run", "--db", db.c_str(), "--participant",
          id.c_str(), "--tracker", "scripted", "--resume", "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

std::int64_t last_trial_id(const std::string& path) {
  Database db(path, Database::Mode::kReadOnly);
  return std::stoll(*db.query_text("SELECT coalesce(max(id), 0) FROM trial"));
}

// Waits until the session `pid` has started a trial (a running trial newer than `after`);
// false when the process ended first, its exit status in `status`.
bool wait_for_running_trial(const std::string& path, std::int64_t after, pid_t pid, int& status) {
  for (;;) {
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    {
      Database db(path, Database::Mode::kReadOnly);
      const auto running = db.query_text(
          "SELECT count(*) FROM trial WHERE status = 'running' "
          "AND id > " +
          std::to_string(after));
      if (running && *running != "0") return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

TEST(CrashTest, SigkillAtRandomMomentsLosesNoTrialAndResumesInOrder) {
  const std::string db = handlab::test::fresh_path("crash.db");
  const std::string reference = handlab::test::fresh_path("crash_reference.db");
  for (const std::string& path : {db, reference})
    ASSERT_EQ(run_cli("study create --protocol " + kStudy + " --db " + path).status, 0);
  const std::vector<std::string> ids = {"P01", "P02", "P03", "P04", "P05", "P06"};
  for (const std::string& id : ids)
    for (const std::string& path : {db, reference})
      ASSERT_EQ(run_cli(enrol(path, id, 0.185)).status, 0);

  std::mt19937 rng(20211004);
  std::uniform_int_distribution<int> delay_ms(15, 400);
  std::uniform_int_distribution<int> in_trial_delay_ms(0, 20);
  int kills = 0;
  int attempts = 0;
  std::size_t participant = 0;
  std::map<std::int64_t, Result_> kept;  // every result seen so far, must never change
  while (participant < ids.size()) {
    const std::string& id = ids[participant];
    const std::int64_t last_trial = last_trial_id(db);
    const pid_t pid = spawn_session(db, id);
    int status = 0;
    bool exited = false;
    if (kills < 20) {
      // Even attempts kill at a moment measured from the start (start-up, between trials or
      // inside one); odd ones wait until this process has a trial running and kill inside it,
      // so that trials are cut however slow the machine is.
      if (attempts++ % 2 == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
      else {
        exited = !wait_for_running_trial(db, last_trial, pid, status);
        if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(in_trial_delay_ms(rng)));
      }
      if (!exited) ::kill(pid, SIGKILL);  // unless it has finished already
    }
    if (!exited) waitpid(pid, &status, 0);
    const bool killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
    kills += killed;
    if (!killed) {
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the session failed";
    }

    Database check(db, Database::Mode::kReadWrite);
    ASSERT_EQ(check.query_text("PRAGMA integrity_check"), "ok") << "after kill " << kills;
    // No result lost or changed, none duplicated, and results in planned order.
    std::map<std::int64_t, Result_> now;
    for (std::size_t k = 0; k <= participant; ++k) {
      std::map<std::int64_t, int> per_planned;
      int last_position = -1;
      for (const auto& [trial, r] : results_of(check, ids[k])) {
        EXPECT_EQ(++per_planned[r.planned_id], 1) << "duplicate result for trial " << r.position;
        EXPECT_GT(r.position, last_position) << "out of planned order";
        last_position = r.position;
        now[trial] = r;
      }
    }
    for (const auto& [trial, r] : kept) {
      ASSERT_TRUE(now.count(trial)) << "a completed trial was lost";
      EXPECT_EQ(now[trial].status, r.status);
      EXPECT_EQ(now[trial].time, r.time);
    }
    kept = now;
    // Every frame of a finished trial is there.
    EXPECT_EQ(check.query_text("SELECT count(*) FROM trial t WHERE status IN ('completed', "
                               "'timeout') AND frames != (SELECT count(*) FROM frame f WHERE "
                               "f.trial_id = t.id)"),
              "0");
    if (!killed) {  // its schedule is complete
      ++participant;
      if (kills >= 20) break;
    }
  }
  EXPECT_GE(kills, 20);

  Database check(db, Database::Mode::kReadWrite);
  const int aborted_seen =
      std::stoi(*check.query_text("SELECT count(*) FROM trial WHERE status = 'aborted'"));
  EXPECT_GT(aborted_seen, 0) << "some kills should land inside a trial";
  // The finished participants' results equal an uninterrupted run's, trial by trial.
  for (std::size_t k = 0; k < participant; ++k) {
    ASSERT_EQ(
        run_cli("session run --db " + reference + " --participant " + ids[k] + " --quiet").status,
        0);
    Database ref(reference, Database::Mode::kReadOnly);
    const auto got = results_of(check, ids[k]);
    const auto want = results_of(ref, ids[k]);
    ASSERT_EQ(got.size(), 20u) << ids[k];
    ASSERT_EQ(want.size(), 20u);
    auto g = got.begin();
    for (auto w = want.begin(); w != want.end(); ++w, ++g) {
      EXPECT_EQ(g->second.position, w->second.position);
      EXPECT_EQ(g->second.time, w->second.time) << ids[k] << " trial " << w->second.position;
    }
  }
  std::printf("%d kills, %d aborted trials kept, %zu participants finished\n", kills, aborted_seen,
              participant);
}

}  // namespace

// The power of the paper's design from its effects file, in the JSON keys scripts read; the
// exact answer in the same shape; the curve drawn; a pilot study's database as the model's
// source (said to be observed power); bad options refused in one line.
TEST(CliPower, SimulatesExactAndFromAPilotInOneShape) {
  const std::string effects =
      std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021-effects.json";
  const std::string base = "power --protocol " + kStudy + " --model " + effects +
                           " --n 10:14:2 --sims 200 --seed 5 --quiet";
  Result r = run_cli(base + " --jobs 2 --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = handlab::util::JsonValue::parse(r.out);
  ASSERT_EQ(doc["n"].size(), 3u);
  EXPECT_EQ(doc["n"][2].as_number(), 14);
  const auto& interaction = doc["effects"]["strategy:manipulation"];
  ASSERT_EQ(interaction.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_GT(interaction[k].as_number(), 0.2);
    EXPECT_LT(interaction[k].as_number(), 0.9);
  }
  const std::string fine = "strategy:manipulation: naive fine - ours fine";
  EXPECT_EQ(doc["contrasts"][fine].size(), 3u);
  EXPECT_GT(doc["mc_se"][fine][0].as_number(), 0.0);
  EXPECT_TRUE(doc["n_for_target"]["strategy:manipulation"].is_null());  // not by N = 14
  EXPECT_EQ(doc["n_for_target"]["manipulation"].is_null(), false);
  // The same seed gives the same powers, on any number of threads.
  const Result again = run_cli(base + " --jobs 1 --json -");
  ASSERT_EQ(again.status, 0) << again.out;
  EXPECT_EQ(handlab::util::JsonValue::parse(again.out)["effects"].dump(), doc["effects"].dump());

  r = run_cli(base + " --exact --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto exact = handlab::util::JsonValue::parse(r.out);
  EXPECT_TRUE(exact["exact"].as_bool());
  EXPECT_EQ(exact["effects"]["strategy:manipulation"].size(), 3u);
  EXPECT_EQ(exact["contrasts"][fine].size(), 3u);
  // Exact and simulated agree within the simulation's error (200 simulations: SE <= 0.035).
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(exact["contrasts"][fine][k].as_number(), doc["contrasts"][fine][k].as_number(),
                0.11);

  // The curve is drawn by a handlab-cli built with Qt (the app's build, with `report`).
  if (run_cli("report --help").status == 0) {
    const std::string svg = handlab::test::fresh_path("power.svg");
    r = run_cli(base + " --plot " + svg + " --plot-name strategy:manipulation --plot-name \"" +
                fine + "\"");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(handlab::test::file_bytes(svg).find("<svg"), std::string::npos);
    EXPECT_NE(run_cli(base + " --plot " + svg + " --plot-name nothing").out.find("'nothing'"),
              std::string::npos);
  } else {
    EXPECT_NE(run_cli(base + " --plot x.svg").out.find("built with Qt"), std::string::npos);
  }

  // A pilot: a small simulated study of two blocks on the grasp proxy (no practice: quick).
  const std::string two_blocks = two_block_protocol("cli_two_blocks.json");
  const std::string pilot = handlab::test::fresh_path("cli_pilot.db");
  r = run_cli("simulate --protocol " + two_blocks + " --participants 3 --seed 2 --db " + pilot +
              " --jobs 2 --world proxy --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  r = run_cli("power --protocol " + two_blocks + " --pilot " + pilot + " --n 6,8 --sims 20");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("observed power"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("strategy:manipulation:repetition"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(Friedman)"), std::string::npos) << r.out;

  one_line_error(
      run_cli("power --protocol " + kStudy + " --model " + effects + " --pilot " + pilot),
      "one of --model FILE or --pilot DB");
  one_line_error(run_cli("power --protocol " + kStudy + " --model " + effects + " --n 10:x"),
                 "--n");
  // A pilot of another design (two blocks) for the five-block protocol.
  one_line_error(run_cli("power --protocol " + kStudy + " --pilot " + pilot), "design");
}

// --pipeline: a whole simulated study (two blocks on the grasp proxy, no practice: quick),
// analysed as analyze --db analyses it, in the same JSON shape.
TEST(CliPower, PipelineAnswersWithWholeSimulatedStudies) {
  const std::string two_blocks = two_block_protocol("cli_power_two_blocks.json");
  const Result r = run_cli("power --protocol " + two_blocks +
                           " --pipeline --world proxy --n 3 --sims 1 --seed 4 --jobs 2 --json -");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = handlab::util::JsonValue::parse(r.out);
  EXPECT_TRUE(doc["pipeline"].as_bool());
  EXPECT_EQ(doc["sims"].as_number(), 1);
  ASSERT_EQ(doc["n"].size(), 1u);
  // The 2x2x2 ANOVA's (at the limit and with the timed-out trials left out), the three
  // participant variables' four each, the success rates' Friedman, the items'.
  EXPECT_EQ(doc["effects"].as_object().size(), 2u * 7u + 3u * 4u + 1u + 3u);
  EXPECT_NO_THROW(doc["effects"]["strategy:manipulation (timeouts left out)"]);
  EXPECT_NO_THROW(doc["effects"]["success_rate (Friedman)"]);
  EXPECT_NO_THROW(doc["effects"]["hand_length:manipulation (covariate)"]);
  for (const auto& [name, power] : doc["effects"].as_object()) {
    ASSERT_EQ(power.size(), 1u) << name;
    const double p = power[0].as_number();
    EXPECT_TRUE(p == 0.0 || p == 1.0) << name << " " << p;  // one study: found or not
  }
  EXPECT_NO_THROW(doc["effects"]["strategy:manipulation:repetition"]);
  // Tukey pairs and the first repetition's two (both ways), the success rates' and the items'
  // pairs.
  EXPECT_EQ(doc["contrasts"].as_object().size(), 2u * (6u + 2u) + 6u + 3 * 6u);
  EXPECT_NO_THROW(doc["contrasts"]["strategy:repetition: naive 1 - ours 1"]);
  EXPECT_EQ(doc["seconds_per_n"].size(), 1u);
  EXPECT_GT(doc["seconds_per_n"][0].as_number(), 0.0);
  one_line_error(run_cli("power --protocol " + two_blocks + " --pipeline --model " + two_blocks),
                 "takes no --model");
}

// The model's sensitivity on whole simulated studies (two parameters, two trajectories of
// three studies each, two people on the grasp proxy: quick): every point a study, each
// output's indices per parameter, the same again with the same seeds, a usage error for a
// parameter the analysis lacks.
TEST(CliSensitivity, MorrisEffectsOfTheModelsParametersOnWholeStudies) {
  const std::string two_blocks = two_block_protocol("cli_sensitivity.json");
  const std::string work = handlab::test::fresh_path("cli_sensitivity_work");
  const std::string command = "sensitivity --protocol " + two_blocks + " --work " + work +
                              " --participants 2 --trajectories 2 --parameter fitts_a "
                              "--parameter practice_rate --jobs 2 --json -";
  const Result r = run_cli(command);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto doc = handlab::util::JsonValue::parse(r.out);
  ASSERT_EQ(doc["parameters"].size(), 2u);
  EXPECT_EQ(doc["parameters"][0]["name"].as_string(), "fitts_a");
  EXPECT_EQ(doc["points"].size(), 2u * 3u);
  ASSERT_EQ(doc["outputs"].size(), 3u);
  EXPECT_EQ(doc["outputs"][1]["test"].as_string(), "repetition");
  for (const auto& output : doc["outputs"].as_array())
    for (const char* name : {"fitts_a", "practice_rate"}) {
      EXPECT_EQ(output["indices"][name]["effects"].as_number(), 2) << name;
      EXPECT_GE(output["indices"][name]["mu_star"].as_number(), 0.0) << name;
    }
  // Faster movements or faster learning change the repetition F of the same people.
  EXPECT_GT(doc["outputs"][1]["indices"]["practice_rate"]["mu_star"].as_number(), 0.0);
  // The same seeds, the same numbers (all but the wall-clock seconds on the first line): a
  // second analysis, in the Release tree only (under the sanitizers it runs no other code).
  const auto numbers = [](const std::string& json) { return json.substr(json.find("\"levels\"")); };
  if (!handlab::test::kUnderSanitizers) {
    EXPECT_EQ(numbers(run_cli(command).out), numbers(r.out));
  }
  one_line_error(run_cli("sensitivity --protocol " + two_blocks + " --work " + work +
                         " --parameter no_such_thing"),
                 "no parameter no_such_thing");
  // An analysis run before, printed, drawn and written again from its JSON: the same tables
  // and the same JSON, byte for byte, without running a study.
  const std::string saved = handlab::test::fresh_path("cli_sensitivity_analysis.json");
  {
    std::ofstream out(saved, std::ios::binary);
    out << r.out;
  }
  const Result tables = run_cli("sensitivity --protocol " + two_blocks + " --from " + saved);
  ASSERT_EQ(tables.status, 0) << tables.out;
  EXPECT_NE(tables.out.find("| fitts_a |"), std::string::npos) << tables.out;
  const Result again =
      run_cli("sensitivity --protocol " + two_blocks + " --from " + saved + " --json -");
  ASSERT_EQ(again.status, 0) << again.out;
  EXPECT_EQ(again.out, r.out);
  one_line_error(run_cli("sensitivity --protocol " + two_blocks + " --from " + two_blocks),
                 "is not a sensitivity analysis");
  one_line_error(run_cli("sensitivity --protocol " + two_blocks + " --from " + saved + ".none"),
                 "cannot read");
  one_line_error(
      run_cli("sensitivity --protocol " + two_blocks + " --from " + saved + " --work " + work),
      "it takes no --work");
}

// Model 2.7.1 only hashes more of what model 2.7 read: the same proxy trials, to the last bit
// of every time, event and answer, as 2.7's binary wrote for the fixture, and in the Release
// build, whose flags wrote it, the same memory to the bit too
// (tests/data/studies/model-2.7-proxy/README.md). The sanitizers' build rounds what the people
// learn differently in the last digits (their trials are the same).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kFixturesBuild = false;
#else
constexpr bool kFixturesBuild = true;
#endif

TEST(CliSimulate, Model271RunsModel27sTrialsToTheBit) {
  const std::string db = handlab::test::fresh_path("model271.db");
  ASSERT_EQ(run_cli("simulate --protocol " + std::string(kStudy) +
                    " --participants 3 --seed 3 --world proxy --db " + db)
                .status,
            0);
  Database study(db, Database::Mode::kQueryOnly);
  std::string dump;
  for (const char* sql :
       {"SELECT 'trial', planned_id, attempt, status, printf('%.17g', completion_time_s), grasps, "
        "drops, reason, frames FROM trial ORDER BY id",
        "SELECT 'event', trial_id, printf('%.17g', t), kind FROM event ORDER BY id",
        "SELECT 'answer', trial_id, item, value FROM answer ORDER BY trial_id, item",
        "SELECT 'memory', trial_id, memory FROM simulated_memory ORDER BY trial_id"}) {
    Statement rows = study.prepare(sql);
    while (rows.step()) {
      for (int c = 0; c < rows.column_count(); ++c)
        dump += (c ? "|" : "") + (rows.is_null(c) ? std::string() : rows.column_text(c));
      dump += '\n';
    }
  }
  std::istringstream got(dump),
      want(handlab::test::file_bytes(std::string(HANDLAB_SOURCE_DIR) +
                                     "/tests/data/studies/model-2.7-proxy/seed3-n3.txt"));
  std::string a, b;
  int lines = 0;
  while (std::getline(want, b)) {
    ASSERT_TRUE(std::getline(got, a)) << "the run ends before the fixture's line " << b;
    if (kFixturesBuild || b.rfind("memory|", 0) != 0) {
      EXPECT_EQ(a, b);
    }
    ++lines;
  }
  EXPECT_FALSE(std::getline(got, a)) << "the run goes on past the fixture: " << a;
  EXPECT_EQ(lines, 458);
  EXPECT_EQ(study.query_text("SELECT model FROM simulated_person LIMIT 1"),
            "handlab participant model 2.7.1");
}
