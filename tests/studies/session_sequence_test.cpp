// Sessions run, killed, resumed, redone and skipped in random order, as an experimenter may:
// whatever the order, each step is done or refused with a message that says what to do, and
// at the end the database holds every planned trial exactly once, by its last attempt.
#include <unistd.h>

#include <filesystem>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/store/sqlite_database.h"
#include "core/store/study_store.h"
#include "studies/session/session_control.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies::session_sequence_test {
namespace {

// Thrown from inside a trial: the process dies there, leaving what a crash leaves on disk.
struct Killed : std::runtime_error {
  Killed() : std::runtime_error("killed") {}
};

// Trials that end at once, as the random sequence decides: what is under test is the
// session's record of them, not the physics (which PipelineTrialDriver's tests cover).
class DecidedTrials : public TrialDriver {
 public:
  explicit DecidedTrials(std::mt19937& rng) : rng_(rng) {}
  int kill_at = -1;  // the trial (counted from 0 in this run) during which the process dies
  retarget::Calibration calibrate(const Protocol&, const store::Participant&) override {
    return {};
  }
  TrialRun run(const TrialSetup&, const FrameSink&) override {
    if (started_++ == kill_at) throw Killed();
    TrialRun r;
    r.success = std::bernoulli_distribution(0.8)(rng_);
    r.completion_time_s = r.success ? 2.0 + std::uniform_real_distribution<>(0, 10)(rng_) : 60.0;
    r.grasps = 1;
    return r;
  }

 private:
  std::mt19937& rng_;
  int started_ = 0;
};

// /dev/shm where there is one: a thousand sequences of committed transactions, each synced.
std::string scratch_folder() {
  const std::string shm = "/dev/shm/handlab-session-sequences-" + std::to_string(::getpid());
  std::error_code ec;
  if (std::filesystem::create_directories(shm, ec) || std::filesystem::is_directory(shm, ec))
    return shm;
  return test::fresh_path("session-sequences");
}

bool says_what_to_do(const std::string& message) {
  return message.find("constraint") == std::string::npos &&
         message.find("SQLite") == std::string::npos;
}

struct Checked {
  int run = 0, refused = 0, killed = 0, redone = 0, skipped = 0;
};

// One step of the sequence; false and a failure when a refusal does not say what to do.
void random_step(const std::string& db_path, std::mt19937& rng, int planned, Checked& seen) {
  store::StudyStore store(db_path);
  const int op = std::uniform_int_distribution<>(0, 4)(rng);
  if (op <= 2) {  // run: fresh, resumed, or killed midway
    const bool resume = op != 0;
    DecidedTrials driver(rng);
    SessionControl control;
    const int budget = std::uniform_int_distribution<>(1, planned)(rng);
    int ended = 0;
    control.trial_ended = [&](const TrialSetup&, const TrialRun&) {
      if (++ended == budget) control.request_stop();
    };
    if (op == 2) driver.kill_at = std::uniform_int_distribution<>(0, budget)(rng);
    SessionRunner runner(store, driver, fixed_responder());
    runner.attach(&control);
    try {
      runner.run("P1", "decided", resume);
      ++seen.run;
    } catch (const Killed&) {
      ++seen.killed;  // the store is dropped without a word, as by a dying process
    } catch (const std::exception& e) {
      EXPECT_TRUE(!resume && std::string(e.what()).find("--resume") != std::string::npos)
          << e.what();
      ++seen.refused;
    }
    return;
  }
  const int position = std::uniform_int_distribution<>(0, planned)(rng);  // one past the end too
  try {
    if (op == 3) {
      store.redo_trial("P1", position, "the tracker lost the hand");
      ++seen.redone;
    } else {
      skip_trial_between_sessions(store, "P1", position, "the participant asked to");
      ++seen.skipped;
    }
  } catch (const std::exception& e) {
    EXPECT_TRUE(says_what_to_do(e.what())) << e.what();
    ++seen.refused;
  }
}

// Every planned trial once: one result (completed, timed out or skipped), its last attempt.
void expect_each_trial_once(const std::string& db_path, int planned) {
  store::Database db(db_path, store::Database::Mode::kReadOnly);
  store::Statement s = db.prepare(
      "SELECT p.position, count(t.id), (SELECT t2.attempt FROM trial t2 WHERE t2.planned_id = "
      "p.id AND t2.status IN ('completed', 'timeout', 'skipped')), max(t.attempt), "
      "sum(t.status = 'running') FROM planned_trial p LEFT JOIN trial t ON t.planned_id = p.id "
      "GROUP BY p.id ORDER BY p.position");
  int rows = 0;
  while (s.step()) {
    ++rows;
    const int position = int(s.column_int64(0));
    ASSERT_GT(s.column_int64(1), 0) << "trial " << position << " never ran";
    EXPECT_EQ(s.column_int64(2), s.column_int64(3)) << "trial " << position;
    EXPECT_EQ(s.column_int64(4), 0) << "trial " << position << " left running";
  }
  EXPECT_EQ(rows, planned);
}

TEST(SessionSequences, AnyOrderOfRunKillResumeRedoSkipEndsWithEachTrialOnceByItsLastAttempt) {
  const std::string text =
      test::with(test::file_bytes(test::kStudy), "\"blocks\": 5", "\"blocks\": 2");
  const Protocol protocol = parse_protocol(text, "two-blocks.json");
  const std::string folder = scratch_folder();
  const std::string base = folder + "/base.db";
  std::filesystem::remove(base);
  store::StudyStore::create(base, study_definition(protocol));
  {
    store::StudyStore store(base);
    store.add_participant(test::participant("P1"), planned_rows(protocol, "P1", 0));
    store.database().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  const int planned = int(protocol.conditions().size()) * protocol.blocks;
  std::mt19937 rng(20261202);
  Checked seen;
  constexpr int kSequences = 1000;
  for (int sequence = 0; sequence < kSequences; ++sequence) {
    const std::string db = folder + "/sequence.db";
    for (const char* side : {"", "-wal", "-shm"}) std::filesystem::remove(db + side);
    std::filesystem::copy_file(base, db);
    const int steps = std::uniform_int_distribution<>(1, 12)(rng);
    for (int k = 0; k < steps; ++k) random_step(db, rng, planned, seen);
    // Then the experimenter finishes the schedule: resumed until complete.
    for (int tries = 0; tries < 3; ++tries) {
      store::StudyStore store(db);
      DecidedTrials driver(rng);
      SessionRunner runner(store, driver, fixed_responder());
      if (runner.run("P1", "decided", true).schedule_complete) break;
    }
    expect_each_trial_once(db, planned);
    if (HasFailure()) {
      ADD_FAILURE() << "sequence " << sequence << " (seed 20261202)";
      break;
    }
  }
  std::filesystem::remove_all(folder);
  // Every kind of step was taken many times over.
  EXPECT_GT(seen.run, 500);
  EXPECT_GT(seen.killed, 300);
  EXPECT_GT(seen.redone, 300);
  EXPECT_GT(seen.skipped, 300);
  EXPECT_GT(seen.refused, 300);
}

}  // namespace
}  // namespace handlab::studies::session_sequence_test
