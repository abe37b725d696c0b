// A simulated participant's questionnaire answers: a latent score per item from what it went
// through in the trial (extra grasp attempts, corrections, losses, time against what it
// expected), with normal noise, rounded to the scale. The mapping and its weights are in
// docs/simulated-participants.md; the condition is not among its inputs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "studies/participant/trial_experience.h"

namespace handlab::studies {

// How much each thing gone through lowers an item's latent score (scale points): each extra
// grasp attempt, each correction, each loss, each doubling of the time against the expected.
struct QuestionnaireWeights {
  double attempt, correction, loss, doubling;
};
// The weights of "precision", "ease" and "naturalness", then of any other item (about their
// mean, the loss's 0.433 as 2.7 ran it); part of the model's hash (participant_model.h).
struct QuestionnaireModel {
  QuestionnaireWeights precision{0.5, 0.3, 0.3, 0.5};
  QuestionnaireWeights ease{0.8, 0.1, 0.5, 1.0};
  QuestionnaireWeights naturalness{0.5, 0.2, 0.5, 0.5};
  QuestionnaireWeights other{0.6, 0.2, 0.433, 2.0 / 3.0};
  double noise_sd = 0.5;  // scale points
};

// One answer per item id (1..scale_points). `time` is the trial's completion time (the
// timeout when it failed). Items other than precision, ease and naturalness take the `other`
// weights.
std::vector<int> simulated_answers(const std::vector<std::string>& item_ids, int scale_points,
                                   const TrialExperience& experience, double time,
                                   std::uint64_t seed);

}  // namespace handlab::studies
