#include "studies/protocol/protocol_store.h"

namespace handlab::studies {

Protocol stored_protocol(store::StudyStore& store) {
  const store::StudyInfo info = store.study();
  return parse_protocol(info.protocol_text, store.path() + " (stored protocol)",
                        ProtocolSource::kStoredStudy);
}

store::StudyDefinition study_definition(const Protocol& protocol) {
  store::StudyDefinition d;
  d.name = protocol.name;
  d.protocol_text = protocol.text;
  d.seed = protocol.seed;
  for (const Factor& f : protocol.factors) d.factors.push_back(f.name);
  for (const Condition& c : protocol.conditions()) {
    std::vector<std::string> levels;
    for (std::size_t f = 0; f < protocol.factors.size(); ++f)
      levels.push_back(protocol.factors[f].levels[std::size_t(c.levels[f])].name);
    d.conditions.emplace_back(c.label, std::move(levels));
  }
  return d;
}

std::vector<store::PlannedTrialRow> planned_rows(const Protocol& protocol,
                                                 const std::string& participant, int enrolment) {
  std::vector<store::PlannedTrialRow> rows;
  for (const PlannedTrial& t : plan_schedule(protocol, participant, enrolment)) {
    store::PlannedTrialRow r;
    r.position = t.position;
    r.block = t.block;
    r.order = t.order;
    r.condition = t.condition;
    r.repetition = t.repetition;
    r.practice = t.practice;
    r.questionnaire = t.questionnaire;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace handlab::studies
