#include "studies/analysis/cube_losses.h"

#include <stdexcept>

namespace handlab::studies {
namespace {

void count(LossCount& c, const store::TrialResultRow& r) {
  ++c.trials;
  if (r.drops > 0)
    ++c.dropped;
  else if (r.grasps > 1)
    ++c.grasped_again;
}

void write_counts(util::JsonWriter& json, const std::vector<LossCount>& counts) {
  json.begin_array();
  for (const LossCount& c : counts)
    json.begin_object()
        .field("label", c.label)
        .field("trials", c.trials)
        .field("dropped", c.dropped)
        .field("grasped_again", c.grasped_again)
        .end_object();
  json.end_array();
}

}  // namespace

CubeLosses cube_losses(store::StudyStore& store, const Protocol& protocol) {
  CubeLosses out;
  for (const Condition& c : protocol.conditions()) out.by_condition.push_back({c.label});
  for (const store::TrialResultRow& r : store.results()) {
    if (r.status == store::TrialStatus::kSkipped) continue;  // nothing was grasped
    if (r.condition < 0 || std::size_t(r.condition) >= out.by_condition.size())
      throw std::runtime_error("a trial of condition " + std::to_string(r.condition) +
                               " that the protocol lacks");
    if (r.repetition < 1) throw std::runtime_error("a trial of repetition below 1");
    while (out.by_repetition.size() < std::size_t(r.repetition))
      out.by_repetition.push_back({std::to_string(out.by_repetition.size() + 1)});
    count(out.by_condition[std::size_t(r.condition)], r);
    count(out.by_repetition[std::size_t(r.repetition - 1)], r);
  }
  return out;
}

void write_cube_losses(util::JsonWriter& json, const CubeLosses& losses) {
  json.begin_object().key("by_condition");
  write_counts(json, losses.by_condition);
  json.key("by_repetition");
  write_counts(json, losses.by_repetition);
  json.end_object();
}

}  // namespace handlab::studies
