#include "studies/session/enrolment.h"

#include <cstdio>
#include <stdexcept>

#include "core/util/sha256.h"
#include "studies/session/session_runner.h"

namespace handlab::studies {

std::vector<FieldProblem> participant_problems(const store::Participant& p,
                                               const std::vector<store::Participant>& enrolled) {
  std::vector<FieldProblem> problems;
  if (p.id.empty() || p.id.size() > 64)
    problems.push_back({"id", "The id is required (1 to 64 characters)."});
  for (const store::Participant& other : enrolled)
    if (other.id == p.id)
      problems.push_back({"id", "A participant " + p.id + " is already enrolled."});
  if (p.age < 5 || p.age > 120) problems.push_back({"age", "The age is between 5 and 120 years."});
  if (p.sex != "F" && p.sex != "M" && p.sex != "X")
    problems.push_back({"sex", "Sex is F, M or X (other or not given)."});
  if (p.handedness != "right" && p.handedness != "left" && p.handedness != "ambidextrous")
    problems.push_back({"handedness", "Handedness is right, left or ambidextrous."});
  if (!(p.hand_length >= 0.10 && p.hand_length <= 0.30))
    problems.push_back({"hand_length",
                        "The hand length (wrist crease to middle fingertip) is between 10 and "
                        "30 cm."});
  if (p.vr_experience.empty())
    problems.push_back({"vr_experience", "The VR experience is required."});
  return problems;
}

int enrol_participant(store::StudyStore& store, const store::Participant& participant) {
  const auto problems = participant_problems(participant, store.participants());
  if (!problems.empty()) throw std::invalid_argument(problems.front().message);
  const Protocol protocol = stored_protocol(store);
  const int enrolment = store.next_enrolment();
  const auto plan = planned_rows(protocol, participant.id, enrolment);
  store.add_participant(participant, plan, enrolment);
  return int(plan.size());
}

void update_participant(store::StudyStore& store, const store::Participant& p) {
  std::vector<store::Participant> others = store.participants();
  std::erase_if(others, [&](const store::Participant& o) { return o.id == p.id; });
  const auto problems = participant_problems(p, others);
  if (!problems.empty()) throw std::invalid_argument(problems.front().message);
  if (!store.participant(p.id))
    throw std::invalid_argument("no participant " + p.id + " to update");
  store.update_participant(p);
}

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
    for (const Level& l : f.levels) levels += (levels.empty() ? "" : ", ") + l.name;
    lines.emplace_back("Factor " + f.name, levels);
  }
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
