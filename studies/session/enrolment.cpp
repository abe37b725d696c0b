#include "studies/session/enrolment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/store/participant_fields.h"
#include "core/util/csv.h"
#include "core/util/sha256.h"
#include "studies/protocol/protocol_store.h"
#include "studies/session/group_assignment.h"

namespace handlab::studies {

std::vector<FieldProblem> participant_problems(const store::Participant& p,
                                               const std::vector<store::Participant>& enrolled,
                                               const Protocol* protocol) {
  std::vector<FieldProblem> problems;
  if (p.id.empty() || p.id.size() > 64)
    problems.push_back({"id", "The id is required (1 to 64 characters)."});
  for (const store::Participant& other : enrolled)
    if (other.id == p.id)
      problems.push_back({"id", "A participant " + p.id + " is already enrolled."});
  auto one_of = [](const auto& allowed, const std::string& value) {
    return std::find(allowed.begin(), allowed.end(), value) != allowed.end();
  };
  if (p.age < store::kMinAge || p.age > store::kMaxAge)
    problems.push_back({"age", "The age is between 5 and 120 years."});
  if (!one_of(store::kSexes, p.sex))
    problems.push_back({"sex", "Sex is F, M or X (other or not given)."});
  if (!one_of(store::kHandednesses, p.handedness))
    problems.push_back({"handedness", "Handedness is right, left or ambidextrous."});
  if (!(p.hand_length >= store::kMinHandLength && p.hand_length <= store::kMaxHandLength))
    problems.push_back({"hand_length",
                        "The hand length (wrist crease to middle fingertip) is between 10 and "
                        "30 cm."});
  if (p.vr_experience.empty())
    problems.push_back({"vr_experience", "The VR experience is required."});
  if (protocol)
    for (const BetweenFactor& f : protocol->between) {
      if (f.assignment != GroupAssignment::kParticipantField) continue;
      try {
        level_from_field(f, p);
      } catch (const std::invalid_argument& e) {
        problems.push_back({f.field, e.what()});
      }
    }
  return problems;
}

int enrol_participant(store::StudyStore& store, const store::Participant& participant) {
  const Protocol protocol = stored_protocol(store);
  const auto problems = participant_problems(participant, store.participants(), &protocol);
  if (!problems.empty()) throw std::invalid_argument(problems.front().message);
  const int enrolment = store.next_enrolment();
  const auto plan = planned_rows(protocol, participant.id, enrolment);
  store::Participant enrolled = participant;
  enrolled.between_levels = assign_groups(protocol, participant, enrolment);
  store.add_participant(enrolled, plan, enrolment);
  return int(plan.size());
}

void update_participant(store::StudyStore& store, const store::Participant& p) {
  std::vector<store::Participant> others = store.participants();
  std::erase_if(others, [&](const store::Participant& o) { return o.id == p.id; });
  const Protocol protocol = stored_protocol(store);
  const auto problems = participant_problems(p, others, &protocol);
  if (!problems.empty()) throw std::invalid_argument(problems.front().message);
  const auto stored = store.participant(p.id);
  if (!stored) throw std::invalid_argument("no participant " + p.id + " to update");
  store::Participant changed = p;
  changed.between_levels = stored->between_levels;  // an enrolment-assigned group stays
  for (const BetweenFactor& f : protocol.between) {
    if (f.assignment != GroupAssignment::kParticipantField) continue;
    const std::string& level = level_from_field(f, p);
    const auto at = std::find_if(changed.between_levels.begin(), changed.between_levels.end(),
                                 [&](const auto& l) { return l.first == f.name; });
    if (at != changed.between_levels.end() && at->second == level) continue;
    // Data recorded in one group are not moved to another.
    if (at != changed.between_levels.end() && store.has_started(p.id))
      throw std::invalid_argument("The " + f.field + " change would move " + p.id + " from " +
                                  f.name + " " + at->second + " to " + level +
                                  " after trials were run; a participant's group is fixed "
                                  "once their schedule has started.");
    if (at == changed.between_levels.end())
      changed.between_levels.emplace_back(f.name, level);
    else
      at->second = level;
  }
  store.update_participant(changed);
}

namespace {

// "novice (none), experienced (yes, some); by vr_experience" or
// "A, B; balanced in order of enrolment".
std::string between_factor_summary(const BetweenFactor& f) {
  std::string out;
  for (const BetweenLevel& l : f.levels) {
    std::string held;
    for (const std::string& v : l.values) held += (held.empty() ? "" : ", ") + v;
    if (f.assignment == GroupAssignment::kParticipantField && held.empty()) {
      const double scale = f.field == "hand_length" ? 100.0 : 1.0;  // cm as the form has it
      const std::string unit = f.field == "hand_length" ? " cm" : " years";
      if (std::isfinite(l.from)) held = "from " + util::format_number(l.from * scale);
      if (std::isfinite(l.below))
        held += (held.empty() ? "" : " ") + std::string("below ") +
                util::format_number(l.below * scale);
      held += unit;
    }
    out += (out.empty() ? "" : ", ") + l.name + (held.empty() ? "" : " (" + held + ")");
  }
  return out + "; " + assignment_rule(f, f.field);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> protocol_summary(const Protocol& protocol) {
  std::vector<std::pair<std::string, std::string>> lines;
  auto cm = [](double m) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g cm", m * 100.0);
    return std::string(text);
  };
  lines.emplace_back("Name", protocol.name);
  if (!protocol.title.empty()) lines.emplace_back("Title", protocol.title);
  for (const Factor& f : protocol.factors) {
    std::string levels;
    for (const Level& l : f.levels)
      levels +=
          (levels.empty() ? "" : ", ") + l.name +
          (l.method && describe(*l.method) != l.name ? " = " + describe(*l.method) : std::string());
    lines.emplace_back("Factor " + f.name, levels);
  }
  for (const BetweenFactor& f : protocol.between)
    lines.emplace_back("Between factor " + f.name, between_factor_summary(f));
  std::string conditions;
  for (const Condition& c : protocol.conditions())
    conditions += (conditions.empty() ? "" : ", ") + c.label;
  lines.emplace_back("Conditions", conditions);
  lines.emplace_back("Blocks", std::to_string(protocol.blocks));
  lines.emplace_back("Counterbalancing",
                     protocol.counterbalancing == Counterbalancing::kRandomizedPerBlock
                         ? "order randomised per participant and block"
                     : protocol.counterbalancing == Counterbalancing::kLatinSquare
                         ? "balanced Latin square"
                         : "fixed order");
  lines.emplace_back("Practice", protocol.practice_per_condition == 0
                                     ? "none"
                                     : std::to_string(protocol.practice_per_condition) +
                                           " trial(s) per condition before the blocks");
  lines.emplace_back("Questionnaire", protocol.questionnaire_timing == QuestionnaireTiming::kNever
                                          ? "none"
                                          : protocol.questionnaire_schedule());
  for (const QuestionnaireItem& item : protocol.items) {
    std::string anchors;
    for (std::size_t k = 0; k < item.anchors.size(); ++k)
      anchors += (k ? " | " : "") + std::to_string(k + 1) + " " + item.anchors[k];
    lines.emplace_back("Item " + item.id, item.text + " (" + anchors + ")");
  }
  lines.emplace_back("Scene", "zone A to B " +
                                  cm((protocol.scene.zone_b - protocol.scene.zone_a).norm()) +
                                  ", zones " + cm(protocol.scene.zone_size) + " wide");
  lines.emplace_back("Simulated hand", cm(protocol.simulated_hand_length) + " long");
  char timing[96];
  std::snprintf(timing, sizeof timing, "timeout %.4g s, the cube at rest in B for %.4g s",
                protocol.timeout_s, protocol.rest_time_s);
  lines.emplace_back("Trials", timing);
  lines.emplace_back("Protocol SHA-256", util::sha256_hex(protocol.text));
  return lines;
}

}  // namespace handlab::studies
