// Who answers the questionnaire after a trial, and what they are told of it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "studies/session/trial_setup.h"

namespace handlab::studies {

// What a questionnaire's responder is told of the trial it answers for: who answers, the
// trial's place, its time limit and the items. Nothing of the condition, the strategy or the
// labels (a person's answers come from what it went through: the TrialRun).
struct SeenQuestionnaire {
  std::string participant_id;
  int position = 0;
  double timeout_s = 0.0;
  std::vector<std::string> item_ids;
  int scale_points = 5;
};

// Answers for the questionnaire after a trial: one value per item, 1..scale.
using QuestionnaireResponder =
    std::function<std::vector<int>(const SeenQuestionnaire&, const TrialRun&)>;

// The scripted participant's answers: the middle of the scale for every item.
QuestionnaireResponder fixed_responder();

// A simulated participant's answers (studies/participant/questionnaire_model.h): from its
// account of the trial (TrialRun::experience), with noise from its own stream under `seed`;
// never from the condition. Without an account, the middle of the scale.
QuestionnaireResponder simulated_responder(std::uint64_t seed);

}  // namespace handlab::studies
