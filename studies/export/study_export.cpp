#include "studies/export/study_export.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "core/util/csv.h"

namespace handlab::studies {
namespace {

using util::csv_field;

std::string number(double x) {
  return util::format_number(x);
}

struct ResultRow {
  std::string participant;
  std::int64_t trial_id;
  int block, order, condition, repetition, attempt, grasps, drops;
  std::string status;
  double completion_time_s;
};

// Final results (completed, timeout or skipped) of non-practice trials, in running order.
std::vector<ResultRow> results(store::StudyStore& store) {
  std::vector<ResultRow> rows;
  store::Statement s = store.database().prepare(
      "SELECT p.participant_id, t.id, p.block, p.order_in_block, p.condition_id, p.repetition, "
      "t.attempt, coalesce(t.grasps, 0), coalesce(t.drops, 0), t.status, "
      "coalesce(t.completion_time_s, 0) FROM trial t JOIN planned_trial p ON p.id = t.planned_id "
      "JOIN participant q ON q.id = p.participant_id WHERE p.practice = 0 AND t.status IN "
      "('completed', 'timeout', 'skipped') ORDER BY q.enrolment, p.position");
  while (s.step())
    rows.push_back({s.column_text(0), s.column_int64(1), int(s.column_int64(2)),
                    int(s.column_int64(3)), int(s.column_int64(4)), int(s.column_int64(5)),
                    int(s.column_int64(6)), int(s.column_int64(7)), int(s.column_int64(8)),
                    s.column_text(9), s.column_double(10)});
  return rows;
}

std::map<std::string, store::Participant> participants_by_id(store::StudyStore& store) {
  std::map<std::string, store::Participant> m;
  for (auto& p : store.participants()) m[p.id] = p;
  return m;
}

void write_covariates(std::ostream& out, const store::Participant& p) {
  out << csv_field(p.id) << ',' << p.age << ',' << csv_field(p.sex) << ','
      << csv_field(p.handedness) << ',' << number(p.hand_length) << ','
      << csv_field(p.vr_experience);
}

void write_design(std::ostream& out, const store::StudyInfo& info, const ResultRow& r) {
  out << ',' << r.block << ',' << r.order;
  for (const std::string& level : info.conditions.at(std::size_t(r.condition)).second)
    out << ',' << csv_field(level);
  out << ',' << r.repetition;
}

constexpr const char* kCovariateHeader = "participant,age,sex,handedness,hand_length,vr_experience";

}  // namespace

void write_trials_csv(store::StudyStore& store, std::ostream& out, bool include_skipped) {
  const store::StudyInfo info = store.study();
  const auto people = participants_by_id(store);
  out << kCovariateHeader << ",block,order";
  for (const std::string& f : info.factors) out << ',' << csv_field(f);
  out << ",repetition,completion_time_s,outcome,grasps,drops,attempt\n";
  for (const ResultRow& r : results(store)) {
    if (r.status == "skipped" && !include_skipped) continue;
    write_covariates(out, people.at(r.participant));
    write_design(out, info, r);
    if (r.status == "skipped")
      out << ",NA,skipped,NA,NA," << r.attempt << '\n';
    else
      out << ',' << number(r.completion_time_s) << ','
          << (r.status == "completed" ? "success" : "timeout") << ',' << r.grasps << ',' << r.drops
          << ',' << r.attempt << '\n';
  }
}

void write_questionnaire_csv(store::StudyStore& store, std::ostream& out) {
  const store::StudyInfo info = store.study();
  const auto people = participants_by_id(store);
  // Item ids in their first-asked order.
  std::vector<std::string> items;
  std::map<std::int64_t, std::map<std::string, int>> answers;
  store::Statement s =
      store.database().prepare("SELECT trial_id, item, value FROM answer ORDER BY rowid");
  while (s.step()) {
    const std::string item = s.column_text(1);
    if (std::find(items.begin(), items.end(), item) == items.end()) items.push_back(item);
    answers[s.column_int64(0)][item] = int(s.column_int64(2));
  }
  out << kCovariateHeader << ",block,order";
  for (const std::string& f : info.factors) out << ',' << csv_field(f);
  out << ",repetition";
  for (const std::string& item : items) out << ',' << csv_field(item);
  out << '\n';
  for (const ResultRow& r : results(store)) {
    const auto found = answers.find(r.trial_id);
    if (found == answers.end()) continue;
    write_covariates(out, people.at(r.participant));
    write_design(out, info, r);
    for (const std::string& item : items) {
      const auto v = found->second.find(item);
      out << ',';
      if (v == found->second.end())
        out << "NA";
      else
        out << v->second;
    }
    out << '\n';
  }
}

std::vector<ParticipantStatus> study_status(store::StudyStore& store) {
  const store::StudyInfo info = store.study();
  std::vector<ParticipantStatus> out;
  for (const store::Participant& p : store.participants()) {
    ParticipantStatus st;
    st.id = p.id;
    st.trials_planned = int(store.plan(p.id).size());
    for (const store::TrialRow& t : store.trials(p.id)) {
      if (t.status == store::TrialStatus::kCompleted || t.status == store::TrialStatus::kTimeout)
        ++st.trials_completed;
      if (t.status == store::TrialStatus::kSkipped) ++st.trials_skipped;
      if (t.status == store::TrialStatus::kAborted) ++st.trials_aborted;
    }
    st.next = store.next_trial(p.id);
    if (st.next) st.next_condition = info.conditions.at(std::size_t(st.next->condition)).first;
    out.push_back(std::move(st));
  }
  return out;
}

}  // namespace handlab::studies
