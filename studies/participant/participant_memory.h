// What a simulated person carries from one trial to the next, built only from what it saw and
// did (its TrialExperience): how many trials it has done, and per cube size it has seen (the
// one cue that tells its trials apart: it never knows the strategy) how often it has handled
// that cube, where it learnt to expect its fingers to meet it and to aim its pads, how far
// past contact it closes and how low on the cube it sets its pads. Stored as JSON with each
// trial's result, so that a resumed session goes on with what it learnt.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "studies/participant/trial_experience.h"
#include "studies/participant/two_rate_adaptation.h"

namespace handlab::studies {

struct CubeMemory {
  double cube_size = 0.0;    // m, as seen
  int trials = 0;            // trials done with it
  TwoRateState contact;      // m: learnt correction of where a pad first meets the cube
  double grip_margin = 0.0;  // m: closing on after contact beyond the loading, from slips
  double grasp_lower = 0.0;  // m: grasping lower on the cube than its first choice, from slips
  TwoRateState caution;      // share of practice's speed-up of the grasp given back (used up to 1)
  // m: learnt shift of where it aims its pads' midpoint across the floor (x, z), against
  // where the pads were when one first touched the cube
  TwoRateState aim_x, aim_z;
};

struct ParticipantMemory {
  int trials = 0;  // trials done
  std::vector<CubeMemory> cubes;

  // What it remembers of a cube of this size (to the millimetre, as it can tell sizes apart);
  // null before it has seen one.
  const CubeMemory* cube(double size) const;
};

// Where it expects a pad to meet the cube after one closing: each closing is a movement of the
// two-state model, adapted by its contact error, or only forgetting when no pad touched.
TwoRateState after_closing(const TwoRateState& contact, const std::optional<double>& error,
                           const TwoRateRates& rates);

// The memory after a trial: its counts advanced, the closing's correction adapted by each
// closing's contact error (after_closing), the aim by where each closing's pads met it and the
// grasp's caution by what its failed grasps added (a trial whose first grasp held only
// forgets), all at `rates`; the grip margin and how much lower it grasps kept as the trial's
// slips left them, or, in a trial without a slip, decayed by `grip_retention`.
ParticipantMemory remember(const ParticipantMemory& memory, const TrialExperience& trial,
                           const TwoRateRates& rates, double grip_retention);

std::string memory_to_json(const ParticipantMemory& memory);
// Throws std::runtime_error on text that is not a memory.
ParticipantMemory memory_from_json(const std::string& text);

}  // namespace handlab::studies
