#include "core/store/study_store.h"

#include "core/store/study_schema.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>
#include <sstream>

#include <sqlite3.h>

#include "core/util/build_info.h"
#include "core/util/json_value.h"
#include "core/util/json_writer.h"
#include "core/util/sha256.h"
#include "core/util/temporary_files.h"

namespace handlab::store {
namespace {

PlannedTrialRow read_planned(const Statement& s) {
  PlannedTrialRow p;
  p.id = s.column_int64(0);
  p.position = int(s.column_int64(1));
  p.block = int(s.column_int64(2));
  p.order = int(s.column_int64(3));
  p.condition = int(s.column_int64(4));
  p.repetition = int(s.column_int64(5));
  p.practice = s.column_int64(6) != 0;
  p.questionnaire = s.column_int64(7) != 0;
  return p;
}

constexpr const char* kParticipantColumns =
    "id, age, sex, handedness, hand_length, vr_experience, notes, enrolment, simulated, "
    "between_levels";

std::string between_levels_json(const Participant& p) {
  std::ostringstream text;
  util::JsonWriter json(text, 0);
  json.begin_object();
  for (const auto& [factor, level] : p.between_levels) json.field(factor, level);
  json.end_object();
  return text.str();
}

std::vector<std::pair<std::string, std::string>> read_between_levels(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> levels;
  const util::JsonValue object = util::JsonValue::parse(text);
  for (const auto& [factor, level] : object.as_object())
    levels.emplace_back(factor, level.as_string());
  return levels;
}

Participant read_participant(const Statement& s) {
  Participant p;
  p.id = s.column_text(0);
  p.age = int(s.column_int64(1));
  p.sex = s.column_text(2);
  p.handedness = s.column_text(3);
  p.hand_length = s.column_double(4);
  p.vr_experience = s.column_text(5);
  p.notes = s.column_text(6);
  p.enrolment = int(s.column_int64(7));
  p.simulated = s.column_int64(8) != 0;
  p.between_levels = read_between_levels(s.column_text(9));
  return p;
}

constexpr const char* kPlannedColumns =
    "id, position, block, order_in_block, condition_id, repetition, practice, questionnaire";

// This build's version and commit, once per file (study_store.h: StudyInfo::programs).
void record_program(Database& db) {
  db.prepare("INSERT OR IGNORE INTO program (version, commit_id) VALUES (?, ?)")
      .bind(1, util::program_version())
      .bind(2, util::build_commit())
      .run();
}

}  // namespace

std::string utc_timestamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()) % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, int(ms.count()));
  return text;
}

void StudyStore::create(const std::string& path, const StudyDefinition& d) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec))
    throw StoreError(path + " already exists: a study database is created once");
  if (d.conditions.empty()) throw StoreError("a study needs at least one condition");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
    throw StoreError("cannot create " + path + ": " +
                     (std::filesystem::exists(folder, ec)
                          ? folder.string() + " is not a folder"
                          : "the folder " + folder.string() + " does not exist"));
  const std::filesystem::path partial = path + ".creating";
  remove_database_files(partial.string());  // a stale one, and its log, of a killed creation
  util::TemporaryDatabase unfinished(partial.string());
  {
    Database db(partial.string(), Database::Mode::kReadWriteCreate);
    Transaction t(db);
    apply_migrations(db, 0, kSchemaVersion);
    db.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
    record_program(db);
    std::ostringstream factors;
    {
      util::JsonWriter w(factors, 0);
      w.string_array(d.factors);
    }
    Statement study = db.prepare(
        "INSERT INTO study (id, name, protocol_text, protocol_sha256, seed, factors, "
        "created_at, planned_participants) VALUES (1, ?, ?, ?, ?, ?, ?, ?)");
    study.bind(1, d.name)
        .bind(2, d.protocol_text)
        .bind(3, util::sha256_hex(d.protocol_text))
        .bind(4, std::int64_t(d.seed))
        .bind(5, factors.str())
        .bind(6, utc_timestamp());
    if (d.planned_participants > 0)
      study.bind(7, std::int64_t(d.planned_participants));
    else
      study.bind_null(7);
    study.run();
    Statement insert = db.prepare("INSERT INTO condition (id, label, levels) VALUES (?, ?, ?)");
    for (std::size_t c = 0; c < d.conditions.size(); ++c) {
      if (d.conditions[c].second.size() != d.factors.size())
        throw StoreError("condition " + d.conditions[c].first + " needs a level of every factor");
      std::ostringstream levels;
      {
        util::JsonWriter w(levels, 0);
        w.string_array(d.conditions[c].second);
      }
      insert.bind(1, std::int64_t(c)).bind(2, d.conditions[c].first).bind(3, levels.str()).run();
    }
    t.commit();
    db.exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  // Appears under its name only once complete.
  std::filesystem::rename(partial, path, ec);
  if (ec) throw StoreError("cannot create " + path + ": " + ec.message());
  unfinished.keep();
  for (const char* side : {"-wal", "-shm"}) std::filesystem::remove(partial.string() + side, ec);
}

StudyStore::Opening StudyStore::opening(const std::string& path, Access access) {
  if (access != Access::kUnfinished) refuse_unfinished_file(path);
  const bool current = checked_study_file(path) == kSchemaVersion;
  if (access != Access::kReadOnly) return {path, Database::Mode::kReadWrite, true};
  return {path, current ? Database::Mode::kQueryOnly : Database::Mode::kMemoryCopy, !current};
}

StudyStore::StudyStore(const std::string& path, Access access)
    : StudyStore(opening(path, access)) {}

StudyStore::StudyStore(const Opening& opening) : db_(opening.path, opening.mode) {
  if (opening.mode == Database::Mode::kReadWrite)
    // A trial's result is the record of a person's time: survive power loss, not just a crash.
    db_.exec("PRAGMA synchronous = FULL");
  if (opening.migrate) migrate();
  if (opening.mode == Database::Mode::kReadWrite) record_program(db_);
}

void StudyStore::migrate() {
  if (pragma_int(db_, "user_version") == kSchemaVersion) return;
  Transaction t(db_);  // then check again under the write lock
  const int version = int(pragma_int(db_, "user_version"));
  if (version > kSchemaVersion)  // another process upgraded it meanwhile
    throw StoreError(db_.path() + " was written by a newer handlab");
  apply_migrations(db_, version, kSchemaVersion);
  t.commit();
}

StudyInfo StudyStore::study() {
  StudyInfo info;
  Statement s = db_.prepare(
      "SELECT name, protocol_text, protocol_sha256, seed, created_at, factors, "
      "IFNULL(planned_participants, 0) FROM study");
  if (!s.step()) throw StoreError(db_.path() + " has no study row");
  info.name = s.column_text(0);
  info.protocol_text = s.column_text(1);
  info.protocol_sha256 = s.column_text(2);
  info.seed = std::uint64_t(s.column_int64(3));
  info.created_at = s.column_text(4);
  const util::JsonValue factors = util::JsonValue::parse(s.column_text(5));
  for (const auto& f : factors.as_array()) info.factors.push_back(f.as_string());
  info.planned_participants = int(s.column_int64(6));
  info.schema_version = int(pragma_int(db_, "user_version"));
  Statement programs = db_.prepare("SELECT version, commit_id FROM program ORDER BY id");
  while (programs.step())
    info.programs.emplace_back(programs.column_text(0), programs.column_text(1));
  Statement c = db_.prepare("SELECT label, levels FROM condition ORDER BY id");
  while (c.step()) {
    std::vector<std::string> levels;
    const util::JsonValue parsed = util::JsonValue::parse(c.column_text(1));
    for (const auto& l : parsed.as_array()) levels.push_back(l.as_string());
    info.conditions.emplace_back(c.column_text(0), std::move(levels));
  }
  return info;
}

StudyCompleteness StudyStore::completeness() {
  StudyCompleteness c;
  c.planned = study().planned_participants;
  std::set<int> places;
  Statement s = db_.prepare("SELECT enrolment FROM participant");
  while (s.step()) places.insert(int(s.column_int64(0)));
  for (int place = 0; place < c.planned; ++place)
    if (!places.count(place)) c.missing_places.push_back(place);
  return c;
}

std::string StudyCompleteness::describe() const {
  if (!partial()) return {};
  std::string text = std::to_string(present()) + " of " + std::to_string(planned) +
                     " planned participants (missing enrolment places";
  for (std::size_t i = 0; i < missing_places.size(); ++i) {
    if (i == 8) {
      text += " and " + std::to_string(missing_places.size() - i) + " more";
      break;
    }
    text += (i ? ", " : " ") + std::to_string(missing_places[i] + 1);
  }
  return text + ")";
}

void StudyStore::add_participant(Participant p, const std::vector<PlannedTrialRow>& plan,
                                 std::optional<int> enrolment) {
  Transaction t(db_);
  if (participant(p.id))
    throw StoreError("participant " + p.id + " already exists in " + db_.path());
  p.enrolment = enrolment ? *enrolment : next_enrolment();
  db_.prepare(
         "INSERT INTO participant (id, enrolment, age, sex, handedness, hand_length, "
         "vr_experience, notes, created_at, simulated, between_levels) VALUES (?, ?, ?, ?, ?, ?, "
         "?, ?, ?, ?, ?)")
      .bind(1, p.id)
      .bind(2, std::int64_t(p.enrolment))
      .bind(3, std::int64_t(p.age))
      .bind(4, p.sex)
      .bind(5, p.handedness)
      .bind(6, p.hand_length)
      .bind(7, p.vr_experience)
      .bind(8, p.notes)
      .bind(9, utc_timestamp())
      .bind(10, std::int64_t(p.simulated ? 1 : 0))
      .bind(11, between_levels_json(p))
      .run();
  Statement insert = db_.prepare(
      "INSERT INTO planned_trial (participant_id, position, block, order_in_block, condition_id, "
      "repetition, practice, questionnaire) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  for (const PlannedTrialRow& r : plan)
    insert.bind(1, p.id)
        .bind(2, std::int64_t(r.position))
        .bind(3, std::int64_t(r.block))
        .bind(4, std::int64_t(r.order))
        .bind(5, std::int64_t(r.condition))
        .bind(6, std::int64_t(r.repetition))
        .bind(7, std::int64_t(r.practice))
        .bind(8, std::int64_t(r.questionnaire))
        .run();
  t.commit();
}

int StudyStore::next_enrolment() {
  return int(std::stoll(
      db_.query_text("SELECT coalesce(max(enrolment) + 1, 0) FROM participant").value()));
}

int StudyStore::participant_count() {
  Statement s = db_.prepare("SELECT count(*) FROM participant");
  s.step();
  return int(s.column_int64(0));
}

std::int64_t StudyStore::frame_count() {
  Statement s = db_.prepare("SELECT count(*) FROM frame");
  s.step();
  return s.column_int64(0);
}

std::int64_t StudyStore::frame_count(std::int64_t trial_id) {
  Statement s = db_.prepare("SELECT count(*) FROM frame WHERE trial_id = ?");
  s.bind(1, trial_id);
  s.step();
  return s.column_int64(0);
}

std::vector<FrameRecord> StudyStore::frames(std::int64_t trial_id) {
  std::vector<FrameRecord> out;
  Statement s = db_.prepare("SELECT data FROM frame WHERE trial_id = ? ORDER BY seq");
  s.bind(1, trial_id);
  while (s.step()) out.push_back(decode_frame(s.column_blob(0)));
  return out;
}

std::vector<Participant> StudyStore::participants() {
  std::vector<Participant> out;
  Statement s = db_.prepare(std::string("SELECT ") + kParticipantColumns +
                            " FROM participant ORDER BY enrolment");
  while (s.step()) out.push_back(read_participant(s));
  return out;
}

std::optional<Participant> StudyStore::participant(const std::string& id) {
  Statement s =
      db_.prepare(std::string("SELECT ") + kParticipantColumns + " FROM participant WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_participant(s);
}

std::vector<PlannedTrialRow> StudyStore::plan(const std::string& participant_id) {
  std::vector<PlannedTrialRow> out;
  Statement s = db_.prepare(std::string("SELECT ") + kPlannedColumns +
                            " FROM planned_trial WHERE participant_id = ? ORDER BY position");
  s.bind(1, participant_id);
  while (s.step()) out.push_back(read_planned(s));
  return out;
}

std::vector<TrialRow> StudyStore::trials(const std::string& participant_id) {
  std::vector<TrialRow> out;
  Statement s = db_.prepare(
      "SELECT t.id, t.planned_id, t.session_id, p.position, t.attempt, t.status, t.started_at, "
      "coalesce(t.ended_at, ''), coalesce(t.reason, ''), coalesce(t.completion_time_s, 0), "
      "coalesce(t.grasps, 0), coalesce(t.drops, 0), t.frames FROM trial t JOIN planned_trial p "
      "ON p.id = t.planned_id WHERE p.participant_id = ? ORDER BY t.id");
  s.bind(1, participant_id);
  while (s.step()) {
    TrialRow r;
    r.id = s.column_int64(0);
    r.planned_id = s.column_int64(1);
    r.session_id = s.column_int64(2);
    r.position = int(s.column_int64(3));
    r.attempt = int(s.column_int64(4));
    r.status = parse_status(s.column_text(5));
    r.started_at = s.column_text(6);
    r.ended_at = s.column_text(7);
    r.reason = s.column_text(8);
    r.completion_time_s = s.column_double(9);
    r.grasps = int(s.column_int64(10));
    r.drops = int(s.column_int64(11));
    r.frames = int(s.column_int64(12));
    out.push_back(std::move(r));
  }
  return out;
}

std::optional<PlannedTrialRow> StudyStore::next_trial(const std::string& participant_id) {
  Statement s = db_.prepare(
      std::string("SELECT ") + kPlannedColumns +
      " FROM planned_trial p WHERE participant_id = ? AND NOT EXISTS (SELECT 1 FROM trial t "
      "WHERE t.planned_id = p.id AND t.status IN ('completed', 'timeout', 'skipped')) ORDER BY "
      "position LIMIT 1");
  s.bind(1, participant_id);
  if (!s.step()) return std::nullopt;
  return read_planned(s);
}

std::int64_t StudyStore::begin_session(const std::string& participant_id,
                                       const std::string& tracker) {
  db_.prepare(
         "INSERT INTO session (participant_id, tracker, started_at, status) VALUES (?, ?, ?, "
         "'running')")
      .bind(1, participant_id)
      .bind(2, tracker)
      .bind(3, utc_timestamp())
      .run();
  return db_.last_insert_rowid();
}

void StudyStore::end_session(std::int64_t session_id, const std::string& status) {
  db_.prepare("UPDATE session SET status = ?, ended_at = ? WHERE id = ?")
      .bind(1, status)
      .bind(2, utc_timestamp())
      .bind(3, session_id)
      .run();
}

bool StudyStore::has_running_session(const std::string& participant_id) {
  Statement s =
      db_.prepare("SELECT count(*) FROM session WHERE participant_id = ? AND status = 'running'");
  s.bind(1, participant_id);
  s.step();
  return s.column_int64(0) > 0;
}

bool StudyStore::has_started(const std::string& participant_id) {
  if (has_running_session(participant_id)) return true;
  // A trial that ran: its result, or an attempt that began (a skip, or a skip redone, ran
  // nothing: redone results keep their completion time).
  Statement s = db_.prepare(
      "SELECT EXISTS (SELECT 1 FROM trial JOIN planned_trial ON trial.planned_id = "
      "planned_trial.id WHERE planned_trial.participant_id = ? AND (trial.status IN ('running', "
      "'aborted', 'completed', 'timeout') OR trial.completion_time_s IS NOT NULL))");
  s.bind(1, participant_id);
  s.step();
  return s.column_int64(0) != 0;
}

void StudyStore::update_participant(const Participant& p) {
  db_.prepare(
         "UPDATE participant SET age = ?, sex = ?, handedness = ?, hand_length = ?, "
         "vr_experience = ?, notes = ?, between_levels = ? WHERE id = ?")
      .bind(1, std::int64_t(p.age))
      .bind(2, p.sex)
      .bind(3, p.handedness)
      .bind(4, p.hand_length)
      .bind(5, p.vr_experience)
      .bind(6, p.notes)
      .bind(7, between_levels_json(p))
      .bind(8, p.id)
      .run();
  if (db_.changes() != 1) throw StoreError("no participant " + p.id + " in " + db_.path());
}

int StudyStore::abort_interrupted(const std::string& participant_id) {
  Transaction t(db_);
  const std::string now = utc_timestamp();
  Statement trials = db_.prepare(
      "UPDATE trial SET status = 'aborted', ended_at = ?, reason = 'interrupted: the session "
      "ended while the trial ran' WHERE status = 'running' AND planned_id IN (SELECT id FROM "
      "planned_trial WHERE participant_id = ?)");
  trials.bind(1, now).bind(2, participant_id).run();
  const int aborted = int(db_.changes());
  db_.prepare(
         "UPDATE session SET status = 'interrupted', ended_at = ? WHERE participant_id = ? "
         "AND status = 'running'")
      .bind(1, now)
      .bind(2, participant_id)
      .run();
  t.commit();
  return aborted;
}

void StudyStore::abort_trial(std::int64_t trial_id, const std::string& reason) {
  db_.prepare(
         "UPDATE trial SET status = 'aborted', ended_at = ?, reason = ? WHERE id = ? AND status "
         "= 'running'")
      .bind(1, utc_timestamp())
      .bind(2, reason)
      .bind(3, trial_id)
      .run();
  if (db_.changes() != 1)
    throw StoreError("trial " + std::to_string(trial_id) + " is not running: cannot abort it");
}

std::int64_t StudyStore::begin_trial(std::int64_t planned_id, std::int64_t session_id) {
  Transaction t(db_);
  Statement attempt =
      db_.prepare("SELECT coalesce(max(attempt), 0) + 1 FROM trial WHERE planned_id = ?");
  attempt.bind(1, planned_id);
  attempt.step();
  db_.prepare(
         "INSERT INTO trial (planned_id, session_id, attempt, status, started_at) VALUES "
         "(?, ?, ?, 'running', ?)")
      .bind(1, planned_id)
      .bind(2, session_id)
      .bind(3, attempt.column_int64(0))
      .bind(4, utc_timestamp())
      .run();
  const std::int64_t id = db_.last_insert_rowid();
  t.commit();
  return id;
}

void StudyStore::finish_trial(std::int64_t trial_id, const TrialOutcome& o) {
  Transaction t(db_);
  db_.prepare(
         "UPDATE trial SET status = ?, ended_at = ?, completion_time_s = ?, grasps = ?, "
         "drops = ?, frames = ? WHERE id = ? AND status = 'running'")
      .bind(1, o.success ? "completed" : "timeout")
      .bind(2, utc_timestamp())
      .bind(3, o.completion_time_s)
      .bind(4, std::int64_t(o.grasps))
      .bind(5, std::int64_t(o.drops))
      .bind(6, std::int64_t(o.frames))
      .bind(7, trial_id)
      .run();
  if (db_.changes() != 1) throw StoreError("trial " + std::to_string(trial_id) + " is not running");
  Statement event = db_.prepare("INSERT INTO event (trial_id, t, kind) VALUES (?, ?, ?)");
  for (const auto& [time, kind] : o.events)
    event.bind(1, trial_id).bind(2, time).bind(3, kind).run();
  Statement answer = db_.prepare("INSERT INTO answer (trial_id, item, value) VALUES (?, ?, ?)");
  for (const auto& [item, value] : o.answers)
    answer.bind(1, trial_id).bind(2, item).bind(3, std::int64_t(value)).run();
  if (!o.participant_memory.empty())
    db_.prepare("INSERT INTO simulated_memory (trial_id, memory) VALUES (?, ?)")
        .bind(1, trial_id)
        .bind(2, o.participant_memory)
        .run();
  t.commit();
}

void StudyStore::add_simulated_person(const SimulatedPersonRow& row) {
  db_.prepare(
         "INSERT INTO simulated_person (participant_id, model, model_sha256, seed, parameters) "
         "VALUES (?, ?, ?, ?, ?)")
      .bind(1, row.participant_id)
      .bind(2, row.model)
      .bind(3, row.model_sha256)
      .bind(4, std::int64_t(row.seed))
      .bind(5, row.parameters)
      .run();
}

std::optional<SimulatedPersonRow> StudyStore::simulated_person(const std::string& participant_id) {
  Statement s = db_.prepare(
      "SELECT model, model_sha256, seed, parameters FROM simulated_person "
      "WHERE participant_id = ?");
  s.bind(1, participant_id);
  if (!s.step()) return std::nullopt;
  return SimulatedPersonRow{participant_id, s.column_text(0), s.column_text(1), s.column_text(3),
                            std::uint64_t(s.column_int64(2))};
}

std::optional<std::string> StudyStore::participant_memory(const std::string& participant_id) {
  Statement s = db_.prepare(
      "SELECT m.memory FROM simulated_memory m JOIN trial t ON t.id = m.trial_id "
      "JOIN planned_trial p ON p.id = t.planned_id WHERE p.participant_id = ? "
      "AND t.status IN ('completed', 'timeout', 'redone') ORDER BY t.id DESC LIMIT 1");
  s.bind(1, participant_id);
  if (!s.step()) return std::nullopt;
  return s.column_text(0);
}

void StudyStore::skip_trial(const std::string& participant_id, int position,
                            std::int64_t session_id, const std::string& reason) {
  if (reason.empty()) throw StoreError("skipping a trial needs a reason");
  Transaction t(db_);
  Statement planned =
      db_.prepare("SELECT id FROM planned_trial WHERE participant_id = ? AND position = ?");
  planned.bind(1, participant_id).bind(2, std::int64_t(position));
  if (!planned.step())
    throw StoreError(participant_id + " has no trial " + std::to_string(position + 1) +
                     " in the schedule (trials are numbered from 1, as study status shows them)");
  const std::int64_t planned_id = planned.column_int64(0);
  Statement result = db_.prepare(
      "SELECT status FROM trial WHERE planned_id = ? AND status IN ('completed', 'timeout', "
      "'skipped')");
  result.bind(1, planned_id);
  if (result.step())
    throw StoreError(participant_id + "'s trial " + std::to_string(position + 1) +
                     " has a result (" + result.column_text(0) +
                     "): redo it first (session redo) if it should not count, then skip it");
  Statement attempt =
      db_.prepare("SELECT coalesce(max(attempt), 0) + 1 FROM trial WHERE planned_id = ?");
  attempt.bind(1, planned_id);
  attempt.step();
  const std::string now = utc_timestamp();
  db_.prepare(
         "INSERT INTO trial (planned_id, session_id, attempt, status, started_at, ended_at, "
         "reason) VALUES (?, ?, ?, 'skipped', ?, ?, ?)")
      .bind(1, planned_id)
      .bind(2, session_id)
      .bind(3, attempt.column_int64(0))
      .bind(4, now)
      .bind(5, now)
      .bind(6, reason)
      .run();
  t.commit();
}

void StudyStore::redo_trial(const std::string& participant_id, int position,
                            const std::string& reason) {
  if (reason.empty()) throw StoreError("redoing a trial needs a reason");
  Transaction t(db_);
  db_.prepare(
         "UPDATE trial SET status = 'redone', reason = ? WHERE status IN ('completed', "
         "'timeout', 'skipped') AND planned_id = (SELECT id FROM planned_trial WHERE "
         "participant_id = ? AND position = ?)")
      .bind(1, reason)
      .bind(2, participant_id)
      .bind(3, std::int64_t(position))
      .run();
  if (db_.changes() != 1)
    throw StoreError(participant_id + "'s trial " + std::to_string(position + 1) +
                     " has no result to redo (it has not run or was redone already; run the "
                     "session to run it)");
  t.commit();
}

}  // namespace handlab::store
