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

// One answer per item id (1..scale_points). `time` is the trial's completion time (the
// timeout when it failed). Items other than precision, ease and naturalness take the mean
// of the three weightings.
std::vector<int> simulated_answers(const std::vector<std::string>& item_ids, int scale_points,
                                   const TrialExperience& experience, double time,
                                   std::uint64_t seed);

}  // namespace handlab::studies
