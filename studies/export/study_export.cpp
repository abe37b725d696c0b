#include "studies/export/study_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/hand/simulated_hand.h"
#include "core/task/cube_task.h"
#include "core/util/csv.h"
#include "studies/protocol/export_columns.h"
#include "studies/protocol/protocol.h"
#include "studies/protocol/protocol_store.h"

namespace handlab::studies {
namespace {

using util::csv_field;

std::string number(double x) {
  return util::format_number(x);
}

// Lengths and times to the micrometre and microsecond: the frame log's float32 record holds
// no finer detail at the scene's size, a trial's time is counted in steps of 1/120 s, and the
// file stays readable.
std::string micro(double x) {
  if (!std::isfinite(x)) return util::format_number(x);
  char text[48];
  std::snprintf(text, sizeof text, "%.6f", x);
  std::string out(text);
  out.erase(out.find_last_not_of('0') + 1);  // 0.150000 -> 0.15, 2.000000 -> 2.
  if (out.back() == '.') out.pop_back();
  return out == "-0" ? "0" : out;
}

template <std::size_t N>
void write_columns(std::ostream& out, const char* const (&columns)[N], bool first = false) {
  for (std::size_t k = 0; k < N; ++k) out << (first && k == 0 ? "" : ",") << columns[k];
}

// Each participant's columns: the form's fields, then their level of each of the protocol's
// between factors (the groups).
class ParticipantColumns {
 public:
  explicit ParticipantColumns(store::StudyStore& store) {
    for (auto& p : store.participants()) people_[p.id] = p;
    for (const BetweenFactor& f : stored_protocol(store).between) between_.push_back(f.name);
  }
  void header(std::ostream& out) const {
    write_columns(out, kParticipantColumns, true);
    for (const std::string& f : between_) out << ',' << csv_field(f);
  }
  void row(std::ostream& out, const std::string& id) const {
    const store::Participant& p = people_.at(id);
    out << csv_field(p.id) << ',' << p.age << ',' << csv_field(p.sex) << ','
        << csv_field(p.handedness) << ',' << number(p.hand_length) << ','
        << csv_field(p.vr_experience);
    for (const std::string& f : between_) {
      const auto level = std::find_if(p.between_levels.begin(), p.between_levels.end(),
                                      [&](const auto& l) { return l.first == f; });
      out << ',' << (level == p.between_levels.end() ? "NA" : csv_field(level->second));
    }
  }

 private:
  std::map<std::string, store::Participant> people_;
  std::vector<std::string> between_;
};

void write_design(std::ostream& out, const store::StudyInfo& info, const store::TrialResultRow& r) {
  out << ',' << r.block << ',' << r.order;
  for (const std::string& level : info.conditions.at(std::size_t(r.condition)).second)
    out << ',' << csv_field(level);
  out << ',' << r.repetition;
}

}  // namespace

void write_trials_csv(store::StudyStore& store, std::ostream& out, bool include_skipped) {
  const store::StudyInfo info = store.study();
  const ParticipantColumns people(store);
  people.header(out);
  write_columns(out, kDesignColumns);
  for (const std::string& f : info.factors) out << ',' << csv_field(f);
  write_columns(out, kTrialColumns);
  out << '\n';
  for (const store::TrialResultRow& r : store.results()) {
    if (r.status == store::TrialStatus::kSkipped && !include_skipped) continue;
    people.row(out, r.participant);
    write_design(out, info, r);
    if (r.status == store::TrialStatus::kSkipped)
      out << ",NA,skipped,NA,NA," << r.attempt << '\n';
    else
      // A time counted in simulation steps (1/120 s) to the microsecond: 858 steps are 7.15 s,
      // not the double's 7.1499999999999995.
      out << ',' << micro(r.completion_time_s) << ','
          << (r.status == store::TrialStatus::kCompleted ? "success" : "timeout") << ',' << r.grasps
          << ',' << r.drops << ',' << r.attempt << '\n';
  }
}

void write_questionnaire_csv(store::StudyStore& store, std::ostream& out) {
  const store::StudyInfo info = store.study();
  const ParticipantColumns people(store);
  // Item ids in their first-asked order.
  std::vector<std::string> items;
  std::map<std::int64_t, std::map<std::string, int>> answers;
  for (const store::AnswerRow& a : store.answers()) {
    if (std::find(items.begin(), items.end(), a.item) == items.end()) items.push_back(a.item);
    answers[a.trial_id][a.item] = a.value;
  }
  people.header(out);
  write_columns(out, kDesignColumns);
  for (const std::string& f : info.factors) out << ',' << csv_field(f);
  out << ",repetition";  // then the items
  for (const std::string& item : items) out << ',' << csv_field(item);
  out << '\n';
  for (const store::TrialResultRow& r : store.results()) {
    const auto found = answers.find(r.trial_id);
    if (found == answers.end()) continue;
    people.row(out, r.participant);
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

void write_frames_csv(store::StudyStore& store, std::ostream& out) {
  const store::StudyInfo info = store.study();
  const ParticipantColumns people(store);
  const std::vector<Condition> conditions = stored_protocol(store).conditions();
  // Per condition: the simulated hand's thumb and index distal bones and their lengths.
  struct Tips {
    int thumb = -1, index = -1;
    double thumb_length = 0.0, index_length = 0.0;
  };
  std::map<int, Tips> tips;
  auto tips_of = [&](int condition) -> const Tips& {
    auto found = tips.find(condition);
    if (found != tips.end()) return found->second;
    const hand::Skeleton hand =
        hand::build_simulated_hand(conditions.at(std::size_t(condition)).simulated_hand);
    Tips t{hand.bone_index("thumb3"), hand.bone_index("index3"), 0.0, 0.0};
    t.thumb_length = hand.bones.at(std::size_t(t.thumb)).length;
    t.index_length = hand.bones.at(std::size_t(t.index)).length;
    return tips.emplace(condition, t).first->second;
  };
  people.header(out);
  write_columns(out, kDesignColumns);
  for (const std::string& f : info.factors) out << ',' << csv_field(f);
  write_columns(out, kFrameColumns);
  out << '\n';
  auto point = [&](const Eigen::Vector3d& p) {
    out << ',' << micro(p.x()) << ',' << micro(p.y()) << ',' << micro(p.z());
  };
  for (const store::TrialResultRow& r : store.results()) {
    if (r.status == store::TrialStatus::kSkipped) continue;
    // The columns every row of this trial shares.
    std::ostringstream head;
    people.row(head, r.participant);
    write_design(head, info, r);
    head << ',' << r.attempt << ','
         << (r.status == store::TrialStatus::kCompleted ? "success" : "timeout");
    const std::string prefix = head.str();
    const Tips& t = tips_of(r.condition);
    for (const store::FrameRecord& f : store.frames(r.trial_id)) {
      out << prefix << ',' << micro(f.time) << ','
          << task::phase_name(task::TaskPhase(f.task_phase));
      point(f.cube_position.cast<double>());
      out << ',' << int(f.thumb_contact) << ',' << int(f.index_contact);
      auto tip = [&](int bone, double length) {
        return Eigen::Vector3d(
            (f.bone_positions.at(std::size_t(bone)) +
             f.bone_rotations.at(std::size_t(bone)) * Eigen::Vector3f(0.0f, float(length), 0.0f))
                .cast<double>());
      };
      if (f.bone_positions.empty()) {
        out << ",NA,NA,NA,NA,NA,NA,NA";
      } else {
        const Eigen::Vector3d thumb = tip(t.thumb, t.thumb_length);
        const Eigen::Vector3d index = tip(t.index, t.index_length);
        point(thumb);
        point(index);
        out << ',' << micro((thumb - index).norm());
      }
      const tracking::TrackedHand* hand = f.tracked.hand(tracking::Side::kRight);
      out << ',' << (hand ? micro(tracking::thumb_index_distance(*hand)) : std::string("NA"))
          << '\n';
    }
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
