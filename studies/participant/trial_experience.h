// What a simulated participant went through in a trial: its questionnaire answers come from
// this, never from the condition.
#pragma once

namespace handlab::studies {

struct TrialExperience {
  int grasp_attempts = 0;      // closings started
  int corrections = 0;         // corrective submovements
  int losses = 0;              // slips, drops and misplacements it saw
  double expected_time = 0.0;  // s: its own plan's nominal duration
};

}  // namespace handlab::studies
