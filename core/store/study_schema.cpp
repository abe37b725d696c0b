#include "core/store/study_schema.h"

#include <filesystem>
#include <iterator>

#include <sqlite3.h>

#include "core/store/study_store.h"

namespace handlab::store {
namespace {

// Schema version k+1 from version k. Never edit a step that has shipped: add one.
constexpr const char* kMigrations[] = {
    // 0 -> 1
    R"sql(
CREATE TABLE study (
  id INTEGER PRIMARY KEY CHECK (id = 1),
  name TEXT NOT NULL,
  protocol_text TEXT NOT NULL,
  protocol_sha256 TEXT NOT NULL CHECK (length(protocol_sha256) = 64),
  seed INTEGER NOT NULL,
  factors TEXT NOT NULL,
  created_at TEXT NOT NULL
);
CREATE TABLE condition (
  id INTEGER PRIMARY KEY CHECK (id >= 0),
  label TEXT NOT NULL UNIQUE,
  levels TEXT NOT NULL
);
CREATE TABLE participant (
  id TEXT PRIMARY KEY CHECK (length(id) BETWEEN 1 AND 64),
  enrolment INTEGER NOT NULL UNIQUE,
  age INTEGER NOT NULL CHECK (age BETWEEN 5 AND 120),
  sex TEXT NOT NULL CHECK (sex IN ('F', 'M', 'X')),
  handedness TEXT NOT NULL CHECK (handedness IN ('right', 'left', 'ambidextrous')),
  hand_length REAL NOT NULL CHECK (hand_length BETWEEN 0.10 AND 0.30),
  vr_experience TEXT NOT NULL,
  notes TEXT NOT NULL DEFAULT '',
  created_at TEXT NOT NULL
);
CREATE TABLE planned_trial (
  id INTEGER PRIMARY KEY,
  participant_id TEXT NOT NULL REFERENCES participant(id),
  position INTEGER NOT NULL CHECK (position >= 0),
  block INTEGER NOT NULL CHECK (block >= 0),
  order_in_block INTEGER NOT NULL CHECK (order_in_block >= 1),
  condition_id INTEGER NOT NULL REFERENCES condition(id),
  repetition INTEGER NOT NULL CHECK (repetition >= 0),
  practice INTEGER NOT NULL CHECK (practice IN (0, 1)),
  questionnaire INTEGER NOT NULL CHECK (questionnaire IN (0, 1)),
  UNIQUE (participant_id, position)
);
CREATE TABLE session (
  id INTEGER PRIMARY KEY,
  participant_id TEXT NOT NULL REFERENCES participant(id),
  tracker TEXT NOT NULL,
  started_at TEXT NOT NULL,
  ended_at TEXT,
  status TEXT NOT NULL CHECK (status IN ('running', 'finished', 'stopped', 'interrupted'))
);
CREATE TABLE trial (
  id INTEGER PRIMARY KEY,
  planned_id INTEGER NOT NULL REFERENCES planned_trial(id),
  session_id INTEGER NOT NULL REFERENCES session(id),
  attempt INTEGER NOT NULL CHECK (attempt >= 1),
  status TEXT NOT NULL
    CHECK (status IN ('running', 'completed', 'timeout', 'aborted', 'skipped', 'redone')),
  started_at TEXT NOT NULL,
  ended_at TEXT,
  completion_time_s REAL CHECK (completion_time_s >= 0),
  grasps INTEGER CHECK (grasps >= 0),
  drops INTEGER CHECK (drops >= 0),
  reason TEXT,
  UNIQUE (planned_id, attempt)
);
-- At most one result per planned trial: a completed trial cannot be duplicated.
CREATE UNIQUE INDEX trial_one_result ON trial(planned_id)
  WHERE status IN ('completed', 'timeout', 'skipped');
CREATE TABLE event (
  id INTEGER PRIMARY KEY,
  trial_id INTEGER NOT NULL REFERENCES trial(id),
  t REAL NOT NULL,
  kind TEXT NOT NULL
);
CREATE TABLE answer (
  trial_id INTEGER NOT NULL REFERENCES trial(id),
  item TEXT NOT NULL,
  value INTEGER NOT NULL CHECK (value >= 1),
  PRIMARY KEY (trial_id, item)
);
-- A rowid table: rows of about a kilobyte are what WITHOUT ROWID tables store badly.
CREATE TABLE frame (
  id INTEGER PRIMARY KEY,
  trial_id INTEGER NOT NULL REFERENCES trial(id),
  seq INTEGER NOT NULL CHECK (seq >= 0),
  t REAL NOT NULL,
  data BLOB NOT NULL,
  UNIQUE (trial_id, seq)
);
)sql",
    // 1 -> 2: frame counts on trials (checked against the frame table), event lookup by trial.
    R"sql(
ALTER TABLE trial ADD COLUMN frames INTEGER NOT NULL DEFAULT 0 CHECK (frames >= 0);
CREATE INDEX event_by_trial ON event(trial_id);
CREATE INDEX trial_by_planned ON trial(planned_id);
)sql",
    // 2 -> 3: participants run by the participant model (handlab-cli simulate) are marked.
    R"sql(
ALTER TABLE participant ADD COLUMN simulated INTEGER NOT NULL DEFAULT 0
  CHECK (simulated IN (0, 1));
)sql",
    // 3 -> 4: simulated participants' model and parameters, and the memory each carries
    // from one trial to the next (so that a resumed session goes on with what it learnt).
    R"sql(
CREATE TABLE simulated_person (
  participant_id TEXT PRIMARY KEY REFERENCES participant(id),
  model TEXT NOT NULL,
  model_sha256 TEXT NOT NULL,
  seed INTEGER NOT NULL,
  parameters TEXT NOT NULL
);
CREATE TABLE simulated_memory (
  trial_id INTEGER PRIMARY KEY REFERENCES trial(id),
  memory TEXT NOT NULL
);
)sql",
    // 4 -> 5: the level of each between-participants factor a participant was assigned,
    // as a JSON object (factor -> level).
    R"sql(
ALTER TABLE participant ADD COLUMN between_levels TEXT NOT NULL DEFAULT '{}';
)sql",
    // 5 -> 6: how many participants a simulated study plans (NULL: a study of people, whose
    // size the experimenter decides), so that a part or a partial merge knows it is one.
    R"sql(
ALTER TABLE study ADD COLUMN planned_participants INTEGER CHECK (planned_participants > 0);
)sql",
    // 6 -> 7: each handlab version and commit that created the file or opened it with write
    // access, in the order they first did.
    R"sql(
CREATE TABLE program (
  id INTEGER PRIMARY KEY,
  version TEXT NOT NULL,
  commit_id TEXT NOT NULL,
  UNIQUE (version, commit_id)
);
)sql",
};
static_assert(std::size(kMigrations) == kSchemaVersion);

}  // namespace

std::int64_t pragma_int(Database& db, const char* pragma) {
  Statement s = db.prepare(std::string("PRAGMA ") + pragma);
  return s.step() ? s.column_int64(0) : 0;
}

// The names under which a study is written before it is complete (StudyStore::create,
// merge_studies, a Slurm task's part): a file left under one was stopped midway.
void refuse_unfinished_file(const std::string& path) {
  if (path.ends_with(".partial"))
    throw StoreError(path +
                     " is an unfinished merge (stopped before it ended): run the merge "
                     "again, which replaces it, and open the study it writes");
  if (path.ends_with(".creating"))
    throw StoreError(path +
                     " is a study database whose creation was stopped before it ended: "
                     "delete it and create the study again");
}

// Inspects the file through a read-only connection before anything may write to it; its
// schema version.
std::int64_t checked_study_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw StoreError("no study database at " + path +
                     " (create one with: handlab-cli study create --protocol FILE --db " + path +
                     ")");
  // SQLite reads the header, never fopen: closing any descriptor of a file drops every POSIX
  // lock this process holds on it, and with them its open connections' guard against another
  // process checkpointing the log under a running session (SQLite's "How To Corrupt", 2.2).
  if (std::filesystem::file_size(path, ec) < 100 || ec)  // SQLite's header is 100 bytes
    throw StoreError(path + " is not a study database (not an SQLite file)");
  Database probe(path, Database::Mode::kInspect);
  std::int64_t application = 0, version = 0;
  try {
    application = pragma_int(probe, "application_id");
    version = pragma_int(probe, "user_version");
  } catch (const StoreError& e) {
    if (probe.last_error_code() == SQLITE_NOTADB)
      throw StoreError(path + " is not a study database (not an SQLite file)");
    const std::string what = e.what();
    throw StoreError(what.find(path) != std::string::npos ? what
                                                          : path + " cannot be read: " + what);
  }
  if (application != kApplicationId)
    throw StoreError(path + " is an SQLite file but not a handlab study database");
  if (version > kSchemaVersion)
    throw StoreError(path + " was written by a newer handlab (schema " + std::to_string(version) +
                     "; this build reads up to " + std::to_string(kSchemaVersion) +
                     "): update handlab; the file was not changed");
  if (version < 1) throw StoreError(path + " is an incomplete study database (schema 0)");
  return version;
}

void apply_migrations(Database& db, int from, int to) {
  for (int v = from; v < to; ++v) db.exec(kMigrations[v]);
  db.exec("PRAGMA user_version = " + std::to_string(to));
}

TrialStatus parse_status(const std::string& s) {
  if (s == "running") return TrialStatus::kRunning;
  if (s == "completed") return TrialStatus::kCompleted;
  if (s == "timeout") return TrialStatus::kTimeout;
  if (s == "aborted") return TrialStatus::kAborted;
  if (s == "skipped") return TrialStatus::kSkipped;
  if (s == "redone") return TrialStatus::kRedone;
  throw StoreError("unknown trial status \"" + s + "\"");
}

}  // namespace handlab::store
