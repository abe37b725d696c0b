// The study database: the protocol a study runs (exact text and hash), its participants,
// their planned schedules, sessions, trials with their events and questionnaire answers,
// and per-frame records. One SQLite file in WAL mode, foreign keys and constraints on;
// every trial's outcome, events and answers commit in one transaction, so a crash costs at
// most the trial that was running. Schema versions migrate forward on open; a file from a
// newer handlab, a file that is not a study database, or a corrupt one is refused without
// being changed. Schema in docs/study.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/store/frame_record.h"
#include "core/store/sqlite_database.h"

namespace handlab::store {

constexpr int kSchemaVersion = 7;

struct StudyDefinition {
  std::string name;
  std::string protocol_text;  // stored byte for byte with its SHA-256
  std::uint64_t seed = 0;
  std::vector<std::string> factors;
  // Per condition: its label and its level of every factor (same order as `factors`).
  std::vector<std::pair<std::string, std::vector<std::string>>> conditions;
  // A simulated study's size, S01 to SNN at enrolment places 0 to N - 1, whether this file
  // holds all of them or a shard (0: no plan, a study of people).
  int planned_participants = 0;
};

struct StudyInfo {
  std::string name, protocol_text, protocol_sha256, created_at;
  std::uint64_t seed = 0;
  int schema_version = 0;
  std::vector<std::string> factors;
  std::vector<std::pair<std::string, std::vector<std::string>>> conditions;
  int planned_participants = 0;  // as StudyDefinition's
  // The handlab versions and commits that created the file or opened it with write access, in the
  // order they first did (none recorded before schema 7).
  std::vector<std::pair<std::string, std::string>> programs;
};

// Whether a study holds every participant its plan names: a shard, or a merge of only some
// shards (merge --partial), is partial until the rest are merged in.
struct StudyCompleteness {
  int planned = 0;                  // 0: no plan (a study of people): never partial
  std::vector<int> missing_places;  // enrolment places 0 .. planned - 1 with no participant
  bool partial() const { return !missing_places.empty(); }
  int present() const { return planned - int(missing_places.size()); }
  // "3 of 4 planned participants (missing S02)"; empty when whole.
  std::string describe() const;
};

struct Participant {
  std::string id;
  int age = 0;
  std::string sex;            // "F", "M", "X" (other or not given)
  std::string handedness;     // "right", "left", "ambidextrous"
  double hand_length = 0.0;   // m, wrist crease to middle fingertip
  std::string vr_experience;  // "none", "some", "yes", "expert" ...
  std::string notes;
  // The level of each between-participants factor of the protocol, in its order, as
  // assigned at enrolment (studies/session/group_assignment.h); empty without such factors.
  std::vector<std::pair<std::string, std::string>> between_levels;
  int enrolment = 0;       // 0-based order of enrolment (set by add_participant)
  bool simulated = false;  // run by the participant model (docs/simulated-participants.md)
};

struct PlannedTrialRow {
  std::int64_t id = 0;
  int position = 0, block = 0, order = 0, condition = 0, repetition = 0;
  bool practice = false, questionnaire = false;
};

enum class TrialStatus { kRunning, kCompleted, kTimeout, kAborted, kSkipped, kRedone };

struct TrialRow {
  std::int64_t id = 0, planned_id = 0, session_id = 0;
  int position = 0, attempt = 0;
  TrialStatus status = TrialStatus::kRunning;
  std::string started_at, ended_at, reason;
  double completion_time_s = 0.0;
  int grasps = 0, drops = 0, frames = 0;
};

// A scheduled trial's result (its attempt that completed, timed out or was skipped), practice
// excluded: what the analyses and exports read.
struct TrialResultRow {
  std::string participant;
  std::int64_t trial_id = 0;
  int block = 0, order = 0, condition = 0, repetition = 0, attempt = 0, grasps = 0, drops = 0;
  TrialStatus status = TrialStatus::kCompleted;
  double completion_time_s = 0.0;
};

// A questionnaire answer given after a trial.
struct AnswerRow {
  std::int64_t trial_id = 0;
  std::string item;
  int value = 0;
};

struct TrialOutcome {
  bool success = false;  // false: timed out
  double completion_time_s = 0.0;
  int grasps = 0, drops = 0, frames = 0;
  std::vector<std::pair<double, std::string>> events;  // (time s, kind)
  std::vector<std::pair<std::string, int>> answers;    // (item id, value)
  // A simulated participant's memory after the trial (its own JSON); empty for people.
  std::string participant_memory;
};

// The participant model a simulated participant was drawn from: its version, the hash of its
// frozen parameters, the population seed and the person's drawn parameters (JSON).
struct SimulatedPersonRow {
  std::string participant_id, model, model_sha256, parameters;
  std::uint64_t seed = 0;
};

class StudyStore {
 public:
  // Creates a new study file; refuses a path that exists.
  static void create(const std::string& path, const StudyDefinition& definition);
  // kReadOnly: a query-only connection (analyses, exports, replays; safe beside a session
  // writing the file): no change to the study is made, an older schema is migrated in a copy
  // in memory, and a file with a rollback journal gets nothing made beside it.
  // kUnfinished: read-write on a file this process is still building under an unfinished
  // name (a merge's OUT.partial); every other access refuses such a name (a study whose
  // writing was stopped midway).
  enum class Access { kReadWrite, kReadOnly, kUnfinished };
  // Opens an existing study file, migrating an older schema forward.
  explicit StudyStore(const std::string& path, Access access = Access::kReadWrite);

  StudyInfo study();
  // The participants the study's plan names and which of them it lacks.
  StudyCompleteness completeness();
  // Enrols a participant with the planned schedule, in one transaction, next in the study's
  // order or at `enrolment` (a shard of a simulated study keeps the whole study's places).
  // Throws StoreError on a duplicate id or place, or a value the schema's constraints reject.
  void add_participant(Participant participant, const std::vector<PlannedTrialRow>& plan,
                       std::optional<int> enrolment = std::nullopt);
  // What may change after enrolment (age, sex, handedness, hand length, VR experience, notes,
  // the between levels a changed field decides); the id, the enrolment order and the schedule
  // stay.
  void update_participant(const Participant& participant);
  int participant_count();
  // The place the next participant takes: one after the last enrolled (a merged or sharded
  // study may have gaps, so not the count).
  int next_enrolment();
  std::int64_t frame_count();  // frames stored, over every trial
  std::int64_t frame_count(std::int64_t trial_id);
  std::vector<FrameRecord> frames(std::int64_t trial_id);  // one trial's, in logged order
  std::optional<Participant> participant(const std::string& id);
  std::vector<Participant> participants();
  std::vector<PlannedTrialRow> plan(const std::string& participant_id);
  std::vector<TrialRow> trials(const std::string& participant_id);  // every attempt, in order
  // The first planned trial without a result (completed, timed out or skipped).
  std::optional<PlannedTrialRow> next_trial(const std::string& participant_id);

  std::int64_t begin_session(const std::string& participant_id, const std::string& tracker);
  void end_session(std::int64_t session_id, const std::string& status);
  // After a crash: trials still "running" become "aborted" (kept, to be run again) and
  // their sessions "interrupted". Returns how many trials were aborted.
  int abort_interrupted(const std::string& participant_id);
  bool has_running_session(const std::string& participant_id);
  // Whether the participant's schedule has started (a session still running, or an attempt
  // at a trial): a session then goes on only as a resumption.
  bool has_started(const std::string& participant_id);

  std::int64_t begin_trial(std::int64_t planned_id, std::int64_t session_id);
  void finish_trial(std::int64_t trial_id, const TrialOutcome& outcome);
  // A running trial stopped before its end: kept as aborted with the reason (it runs again).
  void abort_trial(std::int64_t trial_id, const std::string& reason);
  // The experimenter's decisions, with the reason kept: skip a planned trial (it counts as
  // done), or redo one that has a result (the result stays, marked redone; it runs again).
  void skip_trial(const std::string& participant_id, int position, std::int64_t session_id,
                  const std::string& reason);
  void redo_trial(const std::string& participant_id, int position, const std::string& reason);

  // A simulated participant's model and parameters, stored at enrolment.
  void add_simulated_person(const SimulatedPersonRow& row);
  std::optional<SimulatedPersonRow> simulated_person(const std::string& participant_id);
  // The memory a simulated participant carried out of its last trial with a result (completed
  // or timed out), for the next; none before its first.
  std::optional<std::string> participant_memory(const std::string& participant_id);

  // Every scheduled trial's result, participants in enrolment order, each in schedule order.
  std::vector<TrialResultRow> results();
  // Every questionnaire answer, in the order they were given.
  std::vector<AnswerRow> answers();
  // A compact copy of the whole study into a new file (SQLite's VACUUM INTO).
  void copy_to(const std::string& path);

  // Copies every session of another database of the same study (the same protocol hash),
  // with its trials, events, answers, frames and simulated memories, new ids following this
  // store's. Its participants must be enrolled here with the same schedule; their trials are
  // matched by position. (Sessions run elsewhere: a second lab machine, or simulated participants
  // run side by side, each in a database of its own.)
  void import_sessions(const std::string& path);

  Database& database() { return db_; }
  const std::string& path() const { return db_.path(); }

 private:
  struct Opening {
    std::string path;
    Database::Mode mode;
    bool migrate;
  };
  static Opening opening(const std::string& path, Access access);
  explicit StudyStore(const Opening& opening);
  void migrate();
  Database db_;
};

// "2026-11-22T20:04:03.123Z"
std::string utc_timestamp();

}  // namespace handlab::store
