#include "studies/analysis/condition_outcomes.h"

#include <limits>
#include <stdexcept>

namespace handlab::studies {

std::vector<ConditionOutcome> condition_outcomes(store::StudyStore& store,
                                                 const Protocol& protocol) {
  std::vector<ConditionOutcome> out;
  for (const Condition& c : protocol.conditions()) out.push_back({c.label});
  for (const store::Participant& p : store.participants()) {
    const std::vector<store::TrialRow> trials = store.trials(p.id);
    for (const store::PlannedTrialRow& planned : store.plan(p.id)) {
      const std::size_t c = std::size_t(planned.condition);
      if (c >= out.size())
        throw std::runtime_error("a planned trial of condition " +
                                 std::to_string(planned.condition) + " that the protocol lacks");
      ConditionOutcome& o = out[c];
      const store::TrialRow* last = nullptr;
      for (const store::TrialRow& t : trials) {
        if (t.planned_id != planned.id) continue;
        if (!planned.practice) {
          o.attempts_aborted += t.status == store::TrialStatus::kAborted ? 1 : 0;
          o.attempts_redone += t.status == store::TrialStatus::kRedone ? 1 : 0;
        }
        if (t.status == store::TrialStatus::kCompleted ||
            t.status == store::TrialStatus::kTimeout || t.status == store::TrialStatus::kSkipped)
          last = &t;
      }
      if (planned.practice) {
        o.practice_run += last ? 1 : 0;
        continue;
      }
      ++o.planned;
      if (!last) {
        ++o.not_run;
        continue;
      }
      o.grasps += last->grasps;
      o.drops += last->drops;
      if (last->status == store::TrialStatus::kCompleted) {
        ++o.completed;
        o.mean_time_s += last->completion_time_s;
      } else if (last->status == store::TrialStatus::kTimeout) {
        ++o.timeouts;
      } else {
        ++o.skipped;
      }
    }
  }
  for (ConditionOutcome& o : out)
    if (o.completed > 0) o.mean_time_s /= o.completed;
  return out;
}

void write_condition_outcome(util::JsonWriter& json, const ConditionOutcome& c) {
  json.begin_object();
  write_condition_outcome_fields(json, c);
  json.end_object();
}

void write_condition_outcome_fields(util::JsonWriter& json, const ConditionOutcome& c) {
  json.field("condition", c.condition)
      .field("planned", c.planned)
      .field("completed", c.completed)
      .field("timeouts", c.timeouts)
      .field("skipped", c.skipped)
      .field("not_run", c.not_run)
      // No rate of nothing scheduled: null.
      .field("success_rate", c.planned > 0 ? double(c.completed) / c.planned
                                           : std::numeric_limits<double>::quiet_NaN())
      .field("mean_time_s", c.mean_time_s)
      .field("grasps", c.grasps)
      .field("drops", c.drops);
}

}  // namespace handlab::studies
