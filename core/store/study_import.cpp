#include "core/store/study_store.h"

#include <string>

namespace handlab::store {

void StudyStore::import_sessions(const std::string& path) {
  // ATTACH is refused inside a transaction: attach, copy in one transaction, detach.
  db_.prepare("ATTACH DATABASE ? AS other").bind(1, path).run();
  struct Detach {
    Database& db;
    ~Detach() {
      try {
        db.exec("DETACH DATABASE other");
      } catch (...) {
      }
    }
  } detach{db_};
  if (db_.query_text("SELECT protocol_sha256 FROM other.study") != study().protocol_sha256)
    throw StoreError(path + " is not a database of the study in " + db_.path());
  const auto unmatched = db_.query_text(
      "SELECT count(*) FROM other.planned_trial o LEFT JOIN main.planned_trial m "
      "ON m.participant_id = o.participant_id AND m.position = o.position "
      "AND m.condition_id = o.condition_id WHERE m.id IS NULL");
  if (unmatched != "0")
    throw StoreError(path + " has trials planned differently (" + unmatched.value_or("?") +
                     " unmatched); enrol its participants here with the same schedule first");
  Transaction t(db_);
  // New ids: the other's plus this store's largest, keeping their order.
  auto offset = [&](const char* table) {
    return std::stoll(
        db_.query_text(std::string("SELECT coalesce(max(id), 0) FROM main.") + table).value());
  };
  const std::int64_t session = offset("session"), trial = offset("trial"), event = offset("event"),
                     frame = offset("frame");
  db_.prepare(
         "INSERT INTO main.session (id, participant_id, tracker, started_at, ended_at, status) "
         "SELECT id + ?, participant_id, tracker, started_at, ended_at, status "
         "FROM other.session ORDER BY id")
      .bind(1, session)
      .run();
  db_.prepare(
         "INSERT INTO main.trial (id, planned_id, session_id, attempt, status, started_at, "
         "ended_at, completion_time_s, grasps, drops, reason, frames) "
         "SELECT t.id + ?, m.id, t.session_id + ?, t.attempt, t.status, t.started_at, "
         "t.ended_at, t.completion_time_s, t.grasps, t.drops, t.reason, t.frames "
         "FROM other.trial t JOIN other.planned_trial o ON o.id = t.planned_id "
         "JOIN main.planned_trial m ON m.participant_id = o.participant_id "
         "AND m.position = o.position ORDER BY t.id")
      .bind(1, trial)
      .bind(2, session)
      .run();
  db_.prepare(
         "INSERT INTO main.event (id, trial_id, t, kind) "
         "SELECT id + ?, trial_id + ?, t, kind FROM other.event ORDER BY id")
      .bind(1, event)
      .bind(2, trial)
      .run();
  db_.prepare(
         "INSERT INTO main.answer (trial_id, item, value) "
         "SELECT trial_id + ?, item, value FROM other.answer ORDER BY trial_id, item")
      .bind(1, trial)
      .run();
  db_.prepare(
         "INSERT INTO main.frame (id, trial_id, seq, t, data) "
         "SELECT id + ?, trial_id + ?, seq, t, data FROM other.frame ORDER BY id")
      .bind(1, frame)
      .bind(2, trial)
      .run();
  // (A database of an older schema has none.)
  if (db_.query_text("SELECT count(*) FROM other.sqlite_master WHERE name = 'simulated_memory'") ==
      "1")
    db_.prepare(
           "INSERT INTO main.simulated_memory (trial_id, memory) "
           "SELECT trial_id + ?, memory FROM other.simulated_memory ORDER BY trial_id")
        .bind(1, trial)
        .run();
  t.commit();
}

}  // namespace handlab::store
