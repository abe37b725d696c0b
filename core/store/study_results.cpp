#include "core/store/study_schema.h"
#include "core/store/study_store.h"

namespace handlab::store {

std::vector<TrialResultRow> StudyStore::results() {
  std::vector<TrialResultRow> rows;
  Statement s = db_.prepare(
      "SELECT p.participant_id, t.id, p.block, p.order_in_block, p.condition_id, p.repetition, "
      "t.attempt, coalesce(t.grasps, 0), coalesce(t.drops, 0), t.status, "
      "coalesce(t.completion_time_s, 0) FROM trial t JOIN planned_trial p ON p.id = t.planned_id "
      "JOIN participant q ON q.id = p.participant_id WHERE p.practice = 0 AND t.status IN "
      "('completed', 'timeout', 'skipped') ORDER BY q.enrolment, p.position");
  while (s.step())
    rows.push_back({s.column_text(0), s.column_int64(1), int(s.column_int64(2)),
                    int(s.column_int64(3)), int(s.column_int64(4)), int(s.column_int64(5)),
                    int(s.column_int64(6)), int(s.column_int64(7)), int(s.column_int64(8)),
                    parse_status(s.column_text(9)), s.column_double(10)});
  return rows;
}

std::vector<AnswerRow> StudyStore::answers() {
  std::vector<AnswerRow> rows;
  Statement s = db_.prepare("SELECT trial_id, item, value FROM answer ORDER BY rowid");
  while (s.step()) rows.push_back({s.column_int64(0), s.column_text(1), int(s.column_int64(2))});
  return rows;
}

void StudyStore::copy_to(const std::string& path) {
  db_.prepare("VACUUM INTO ?").bind(1, path).run();
}

}  // namespace handlab::store
