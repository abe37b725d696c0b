// The study database: schema, constraints, migrations, refusals that leave the file alone,
// and frames logged off the caller's thread without loss.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/store/frame_logger.h"
#include "core/store/frame_record.h"
#include "core/store/study_store.h"
#include "core/util/build_info.h"
#include "tests/support/test_files.h"

namespace handlab::store {
namespace {

StudyDefinition definition() {
  StudyDefinition d;
  d.name = "test";
  d.protocol_text = "{\"any\": \"text\"}";
  d.seed = 7;
  d.factors = {"strategy", "manipulation"};
  d.conditions = {{"naive-gross", {"naive", "gross"}}, {"ours-fine", {"ours", "fine"}}};
  return d;
}

Participant person(const std::string& id) {
  Participant p;
  p.id = id;
  p.age = 26;
  p.sex = "F";
  p.handedness = "right";
  p.hand_length = 0.188;
  p.vr_experience = "yes";
  return p;
}

std::vector<PlannedTrialRow> two_trials() {
  PlannedTrialRow a, b;
  a.position = 0, a.block = 1, a.order = 1, a.condition = 0, a.repetition = 1;
  b.position = 1, b.block = 1, b.order = 2, b.condition = 1, b.repetition = 1,
  b.questionnaire = true;
  return {a, b};
}

// The message of what `f` throws (empty if nothing).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

TEST(StudyStore, CreatesOpensAndKeepsTheProtocolWithItsHash) {
  const std::string path = test::fresh_path("store_basic.db");
  StudyStore::create(path, definition());
  EXPECT_NE(error_of([&] { StudyStore::create(path, definition()); }).find("already exists"),
            std::string::npos);
  StudyStore db(path);
  const StudyInfo info = db.study();
  EXPECT_EQ(info.protocol_text, "{\"any\": \"text\"}");
  EXPECT_EQ(info.protocol_sha256.size(), 64u);
  EXPECT_EQ(info.schema_version, kSchemaVersion);
  EXPECT_EQ(info.factors, definition().factors);
  ASSERT_EQ(info.conditions.size(), 2u);
  EXPECT_EQ(info.conditions[1].second[1], "fine");
  EXPECT_EQ(db.database().query_text("PRAGMA journal_mode"), "wal");
  EXPECT_EQ(db.database().query_text("PRAGMA foreign_keys"), "1");
}

// The edit form's change: the values that may change do, the enrolment and the schedule
// stay, and an unknown id is refused without touching anything.
TEST(StudyStore, UpdatesAParticipantKeepingTheSchedule) {
  const std::string path = test::fresh_path("store_update.db");
  StudyStore::create(path, definition());
  StudyStore db(path);
  db.add_participant(person("P01"), two_trials());
  Participant changed = person("P01");
  changed.age = 40;
  changed.sex = "X";
  changed.handedness = "left";
  changed.hand_length = 0.171;
  changed.vr_experience = "none";
  changed.notes = "age corrected, \"was 26\"";
  db.update_participant(changed);
  const auto back = db.participant("P01");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->age, 40);
  EXPECT_EQ(back->sex, "X");
  EXPECT_EQ(back->handedness, "left");
  EXPECT_DOUBLE_EQ(back->hand_length, 0.171);
  EXPECT_EQ(back->vr_experience, "none");
  EXPECT_EQ(back->notes, "age corrected, \"was 26\"");
  EXPECT_EQ(back->enrolment, 0);
  EXPECT_EQ(db.plan("P01").size(), 2u);
  EXPECT_NE(error_of([&] { db.update_participant(person("P02")); }).find("no participant P02"),
            std::string::npos);
  EXPECT_EQ(db.participant_count(), 1);
}

TEST(StudyStore, ParticipantsTrialsAndConstraints) {
  const std::string path = test::fresh_path("store_trials.db");
  StudyStore::create(path, definition());
  StudyStore db(path);
  db.add_participant(person("P01"), two_trials());
  EXPECT_NE(
      error_of([&] { db.add_participant(person("P01"), two_trials()); }).find("already exists"),
      std::string::npos);
  Participant bad = person("P02");
  bad.hand_length = 1.88;  // centimetres by mistake
  EXPECT_NE(error_of([&] { db.add_participant(bad, two_trials()); }).find("CHECK"),
            std::string::npos);
  EXPECT_FALSE(db.participant("P02")) << "nothing of a rejected enrolment is kept";
  db.add_participant(person("P03"), two_trials());
  EXPECT_EQ(db.participant("P03")->enrolment, 1);

  const std::int64_t session = db.begin_session("P01", "scripted");
  auto next = db.next_trial("P01");
  ASSERT_TRUE(next);
  EXPECT_EQ(next->position, 0);
  const std::int64_t t1 = db.begin_trial(next->id, session);
  TrialOutcome o;
  o.success = true;
  o.completion_time_s = 4.5;
  o.grasps = 1;
  o.events = {{0.0, "start"}, {1.0, "grasp"}, {4.5, "done"}};
  db.finish_trial(t1, o);
  EXPECT_THROW(db.finish_trial(t1, o), StoreError) << "a trial ends once";
  // A second result for the same planned trial violates the schema itself.
  EXPECT_THROW(db.database().exec("INSERT INTO trial (planned_id, session_id, attempt, status, "
                                  "started_at) VALUES (" +
                                  std::to_string(next->id) + ", " + std::to_string(session) +
                                  ", 9, 'completed', 'x')"),
               StoreError);
  // Answers out of range roll the whole trial back: no half-written trial.
  next = db.next_trial("P01");
  EXPECT_EQ(next->position, 1);
  const std::int64_t t2 = db.begin_trial(next->id, session);
  TrialOutcome bad_answer = o;
  bad_answer.answers = {{"precision", 4}, {"ease", 0}};
  EXPECT_THROW(db.finish_trial(t2, bad_answer), StoreError);
  EXPECT_EQ(db.trials("P01")[1].status, TrialStatus::kRunning);
  store::Statement events = db.database().prepare("SELECT count(*) FROM event WHERE trial_id = ?");
  events.bind(1, t2);
  events.step();
  EXPECT_EQ(events.column_int64(0), 0);

  // A crash here: the running trial becomes aborted, is kept, and runs again.
  EXPECT_EQ(db.abort_interrupted("P01"), 1);
  EXPECT_EQ(db.trials("P01")[1].status, TrialStatus::kAborted);
  EXPECT_EQ(db.next_trial("P01")->position, 1);
  const std::int64_t s2 = db.begin_session("P01", "scripted");
  const std::int64_t t3 = db.begin_trial(next->id, s2);
  o.answers = {{"precision", 4}, {"ease", 5}};
  db.finish_trial(t3, o);
  const auto trials = db.trials("P01");
  ASSERT_EQ(trials.size(), 3u);
  EXPECT_EQ(trials[2].attempt, 2);
  EXPECT_FALSE(db.next_trial("P01"));

  db.skip_trial("P03", 0, s2, "tracker lost the hand");
  EXPECT_EQ(db.next_trial("P03")->position, 1);
  EXPECT_THROW(db.redo_trial("P03", 1, "no result yet"), StoreError);
  EXPECT_THROW(db.skip_trial("P03", 1, s2, ""), StoreError) << "a reason is required";
}

TEST(StudyStore, MigratesAnOlderSchemaForward) {
  const std::string path = test::fresh_path("store_v1.db");
  StudyStore::create(path, definition());
  {
    StudyStore db(path);
    db.add_participant(person("P01"), two_trials());
    // Back to schema 1 as a file of the first release looked.
    db.database().exec(
        "DROP INDEX event_by_trial; DROP INDEX trial_by_planned; ALTER TABLE trial DROP COLUMN "
        "frames; ALTER TABLE participant DROP COLUMN simulated; DROP TABLE simulated_person; "
        "DROP TABLE simulated_memory; ALTER TABLE participant DROP COLUMN between_levels; "
        "ALTER TABLE study DROP COLUMN planned_participants; DROP TABLE program; "
        "PRAGMA user_version = 1");
  }
  StudyStore db(path);
  EXPECT_EQ(db.study().schema_version, kSchemaVersion);
  ASSERT_TRUE(db.participant("P01"));
  EXPECT_FALSE(db.participant("P01")->simulated);  // a person, as everyone before schema 3
  Participant model = person("S01");
  model.simulated = true;
  db.add_participant(model, {});
  EXPECT_TRUE(db.participant("S01")->simulated);
  EXPECT_EQ(db.trials("P01").size(), 0u);
  const std::int64_t s = db.begin_session("P01", "x");
  const std::int64_t t = db.begin_trial(db.next_trial("P01")->id, s);
  TrialOutcome o;
  o.frames = 12;
  o.participant_memory = "{\"trials\":1}";
  db.finish_trial(t, o);
  EXPECT_EQ(db.trials("P01")[0].frames, 12);
  // Schema 4: a simulated participant's model and the memory it carries.
  EXPECT_EQ(db.participant_memory("P01"), "{\"trials\":1}");
  EXPECT_FALSE(db.simulated_person("S01"));
  db.add_simulated_person({"S01", "model 2", "abc", "{}", 7});
  EXPECT_EQ(db.simulated_person("S01")->seed, 7u);
  EXPECT_EQ(db.simulated_person("S01")->model_sha256, "abc");
  // Schema 5: the groups of between-participants factors; none for those enrolled before.
  EXPECT_TRUE(db.participant("P01")->between_levels.empty());
  Participant grouped = person("G01");
  grouped.between_levels = {{"glove", "on"}, {"experience", "novice"}};  // the protocol's order
  db.add_participant(grouped, {});
  EXPECT_EQ(db.participant("G01")->between_levels, grouped.between_levels);
  // Schema 6: a study made before plans no size and is never partial.
  EXPECT_EQ(db.study().planned_participants, 0);
  EXPECT_FALSE(db.completeness().partial());
  // Schema 7: the versions that wrote it, from this one on (opened here to write).
  ASSERT_EQ(db.study().programs.size(), 1u);
  EXPECT_EQ(db.study().programs[0].first, util::program_version());
}

// The file names the handlab that made it and each other one that opened it to write, once
// each; reading it names nobody.
TEST(StudyStore, RecordsTheVersionsThatWroteIt) {
  const std::string path = test::fresh_path("store_programs.db");
  StudyStore::create(path, definition());
  const std::pair<std::string, std::string> self = {util::program_version(), util::build_commit()};
  EXPECT_EQ(StudyStore(path).study().programs, std::vector{self});
  { StudyStore(path).database().exec("UPDATE program SET version = '0.27.0'"); }
  EXPECT_EQ(StudyStore(path, StudyStore::Access::kReadOnly).study().programs.size(), 1u);
  const auto programs = StudyStore(path).study().programs;
  ASSERT_EQ(programs.size(), 2u);
  EXPECT_EQ(programs[0].first, "0.27.0");
  EXPECT_EQ(programs[1], self);
}

// Analyses open a study read-only: a file committed with a rollback journal (as the test
// studies are) is left byte for byte with nothing beside it, and an older schema is read
// through a copy migrated in memory.
TEST(StudyStore, ReadOnlyAccessWritesNothing) {
  const std::string path = test::fresh_path("store_read_only.db");
  StudyStore::create(path, definition());
  {
    StudyStore db(path);
    db.add_participant(person("P01"), two_trials());
    db.database().exec(
        "ALTER TABLE participant DROP COLUMN simulated; DROP TABLE simulated_person; "
        "DROP TABLE simulated_memory; ALTER TABLE participant DROP COLUMN between_levels; "
        "ALTER TABLE study DROP COLUMN planned_participants; DROP TABLE program; "
        "PRAGMA user_version = 2");
  }
  { Database(path, Database::Mode::kInspect).exec("PRAGMA journal_mode = DELETE"); }
  ASSERT_FALSE(std::filesystem::exists(path + "-wal"));
  const std::string before = test::file_bytes(path);
  for (int k = 0; k < 2; ++k) {
    StudyStore db(path, StudyStore::Access::kReadOnly);
    EXPECT_EQ(db.study().schema_version, kSchemaVersion);
    ASSERT_TRUE(db.participant("P01"));
    EXPECT_FALSE(db.participant("P01")->simulated);
    EXPECT_EQ(db.plan("P01").size(), 2u);
  }
  EXPECT_EQ(test::file_bytes(path), before);
  { StudyStore upgraded(path); }  // the schema current, still no writes by a reader
  { Database(path, Database::Mode::kInspect).exec("PRAGMA journal_mode = DELETE"); }
  const std::string current = test::file_bytes(path);
  {
    StudyStore db(path, StudyStore::Access::kReadOnly);
    EXPECT_EQ(db.plan("P01").size(), 2u);
    EXPECT_THROW(db.add_participant(person("P02"), two_trials()), StoreError);
  }
  EXPECT_EQ(test::file_bytes(path), current);
  EXPECT_FALSE(std::filesystem::exists(path + "-wal"));
  EXPECT_FALSE(std::filesystem::exists(path + "-shm"));
}

TEST(StudyStore, RefusesBadFilesWithoutChangingThem) {
  const std::string newer = test::fresh_path("store_newer.db");
  StudyStore::create(newer, definition());
  { Database(newer, Database::Mode::kReadWrite).exec("PRAGMA user_version = 99"); }
  const std::string text = test::fresh_path("store_text.db");
  std::ofstream(text) << "participant,age\nP01,26\n";
  const std::string foreign = test::fresh_path("store_foreign.db");
  { Database(foreign).exec("CREATE TABLE x (a); INSERT INTO x VALUES (1)"); }
  const std::string truncated = test::fresh_path("store_truncated.db");
  {
    StudyStore::create(truncated, definition());
    StudyStore db(truncated);
    std::vector<PlannedTrialRow> many;
    for (int k = 0; k < 2000; ++k) {
      PlannedTrialRow r;
      r.position = k, r.block = 1, r.order = 1;
      many.push_back(r);
    }
    db.add_participant(person("P01"), many);
    db.database().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  std::filesystem::resize_file(truncated, std::filesystem::file_size(truncated) / 3);

  struct Case {
    std::string path, message;
  };
  for (const Case& c : {Case{newer, "newer handlab"}, Case{text, "not an SQLite file"},
                        Case{foreign, "not a handlab study database"},
                        Case{test::fresh_path("store_missing.db"), "no study database"}}) {
    const bool existed = std::filesystem::exists(c.path);
    const std::string before = existed ? test::file_bytes(c.path) : "";
    const std::string message = error_of([&] { StudyStore db(c.path); });
    EXPECT_NE(message.find(c.message), std::string::npos) << c.path << ": " << message;
    EXPECT_EQ(std::filesystem::exists(c.path), existed) << c.path;
    if (existed) {
      EXPECT_EQ(test::file_bytes(c.path), before) << c.path;
    }
  }
  // A truncated file opens (its first page is intact) but reading what is gone is an error,
  // not a crash, and writing to it is refused.
  const std::string before = test::file_bytes(truncated);
  const std::string message = error_of([&] {
    StudyStore db(truncated);
    db.plan("P01");
    db.add_participant(person("P02"), two_trials());
  });
  EXPECT_FALSE(message.empty());
  EXPECT_EQ(test::file_bytes(truncated), before);
}

TEST(StudyStore, LockedFileIsReportedNotWaitedOnForever) {
  const std::string path = test::fresh_path("store_locked.db");
  StudyStore::create(path, definition());
  const std::string before = test::file_bytes(path);
  Database holder(path, Database::Mode::kReadWrite);
  holder.exec("PRAGMA locking_mode = EXCLUSIVE; BEGIN EXCLUSIVE");
  const std::string message = error_of([&] {
    StudyStore db(path);
    db.add_participant(person("P01"), two_trials());
  });
  EXPECT_NE(message.find("locked"), std::string::npos) << message;
  holder.exec("ROLLBACK");
}

FrameRecord sample_frame(double t) {
  FrameRecord f;
  f.time = t;
  f.tracked.timestamp = t;
  f.tracked.id = 42;
  tracking::TrackedHand h;
  h.pinch_strength = 0.25;
  for (int d = 0; d < 5; ++d)
    for (int k = 0; k < 5; ++k) h.joints[std::size_t(d)][std::size_t(k)] = Eigen::Vector3d(d, k, t);
  f.tracked.hands.push_back(h);
  f.root_position = Eigen::Vector3f(1, 2, 3);
  f.root_rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitY()));
  f.angles.assign(21, 0.125f);
  for (int b = 0; b < 16; ++b) {
    f.bone_positions.push_back(Eigen::Vector3f(float(b), 0, 0));
    f.bone_rotations.push_back(Eigen::Quaternionf::Identity());
  }
  f.cube_position = Eigen::Vector3f(0.1f, 0.005f, 0);
  f.task_phase = 2;
  f.index_contact = true;
  return f;
}

TEST(FrameRecord, RoundTripsAndRejectsDamage) {
  const FrameRecord f = sample_frame(0.5);
  std::vector<std::uint8_t> blob;
  encode_frame(f, blob);
  const FrameRecord g = decode_frame(blob);
  EXPECT_EQ(g.time, 0.5);
  ASSERT_EQ(g.tracked.hands.size(), 1u);
  EXPECT_EQ(g.tracked.hands[0].joints[3][2], Eigen::Vector3d(3, 2, 0.5));
  EXPECT_EQ(g.tracked.hands[0].pinch_strength, 0.25);
  EXPECT_EQ(g.angles, f.angles);
  EXPECT_EQ(g.bone_positions[7], f.bone_positions[7]);
  EXPECT_TRUE(g.root_rotation.isApprox(f.root_rotation));
  EXPECT_EQ(g.task_phase, 2);
  EXPECT_TRUE(g.index_contact);
  EXPECT_FALSE(g.thumb_contact);
  std::vector<std::uint8_t> cut(blob.begin(), blob.end() - 3);
  EXPECT_THROW(decode_frame(cut), std::runtime_error);
  blob.push_back(0);
  EXPECT_THROW(decode_frame(blob), std::runtime_error);
}

TEST(FrameLogger, CommitsEveryFrameOffTheCallersThread) {
  const std::string path = test::fresh_path("store_frames.db");
  StudyStore::create(path, definition());
  StudyStore db(path);
  db.add_participant(person("P01"), two_trials());
  const std::int64_t session = db.begin_session("P01", "x");
  const std::int64_t trial = db.begin_trial(db.next_trial("P01")->id, session);
  const int n = 5000;
  {
    FrameLogger logger(path, 64);
    for (int k = 0; k < n; ++k) logger.log(trial, k, sample_frame(k / 120.0));
    logger.flush();
    EXPECT_EQ(logger.committed(), std::size_t(n));
    for (int k = n; k < n + 10; ++k) logger.log(trial, k, sample_frame(k / 120.0));
  }  // the destructor commits the rest
  Statement count = db.database().prepare("SELECT count(*), min(seq), max(seq) FROM frame");
  count.step();
  EXPECT_EQ(count.column_int64(0), n + 10);
  EXPECT_EQ(count.column_int64(1), 0);
  EXPECT_EQ(count.column_int64(2), n + 9);
  // Read back as logged, in order.
  EXPECT_EQ(db.frame_count(trial), n + 10);
  EXPECT_EQ(db.frame_count(trial + 1), 0);
  const std::vector<FrameRecord> back = db.frames(trial);
  ASSERT_EQ(back.size(), std::size_t(n + 10));
  for (int k : {0, 1, n / 2, n + 9}) EXPECT_DOUBLE_EQ(back[std::size_t(k)].time, k / 120.0);
  // A duplicate frame is a writer error that reaches the caller.
  FrameLogger logger(path, 1);
  logger.log(trial, 3, sample_frame(0));
  EXPECT_THROW(logger.flush(), StoreError);
}

}  // namespace
}  // namespace handlab::store
