// What a simulated participant went through in a trial, as it saw it: its questionnaire
// answers and what it carries to its next trial (participant_memory.h) come from this, never
// from the condition.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "studies/participant/activity_time.h"

namespace handlab::studies {

struct TrialExperience {
  int grasp_attempts = 0;      // closings started
  int corrections = 0;         // corrective submovements
  int losses = 0;              // slips, drops and misplacements it saw
  double expected_time = 0.0;  // s: its own plan's nominal duration
  double cube_size = 0.0;      // m: the cube it saw
  // Each closing's contact error, in order: its own aperture where it first saw a pad on the
  // cube minus where it expected a pad to meet it (m; > 0: sooner than expected); none for a
  // closing in which it saw no pad touch the cube.
  std::vector<std::optional<double>> contact_errors{};
  // Each closing's aim error, for the closings in which it saw a pad touch the cube:
  // where it saw its pads' midpoint when the first pad touched, minus the cube's centre,
  // across the floor (x, z; m).
  std::vector<std::array<double, 2>> aim_errors{};
  // Cubes it saw lost from its pads under load (lifted, carried, lowered): what its memory
  // learns from (time.slips counts the same for the account of its time only).
  int slips = 0;
  // m: how much further past contact the slips that the pads let go made it close in this
  // trial, and how much lower on the cube the slips that the pads slid over made it grasp,
  // against where it started: what the trial showed it needed.
  double squeeze_added = 0.0;
  double lowered = 0.0;
  // How much of practice's speed-up of the grasp its failed grasps (closings that missed the
  // cube, cubes that slipped under load) gave back in this trial: what the trial showed of
  // its speed against its accuracy.
  double caution_added = 0.0;
  // Where the trial's time went (one trial; counting only: nothing it does depends on it).
  ActivityTime time{.trials = 1};
};

}  // namespace handlab::studies
