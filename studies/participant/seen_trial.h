// What a simulated participant knows of a trial before it starts, besides who it is and what it
// remembers: the trial's place in its session and how the simulated hand looks. The simulated
// tracker builds it from the trial's condition (seen_trial_of, studies/session/trial_display.cpp),
// the one place where a condition is reduced to what a person sees; the participant and its
// questionnaire answers are built from this alone. Nothing of the strategy, the condition or
// its label has a field here (SimulatedParticipantBlinding).
#pragma once

#include "studies/participant/observation.h"

namespace handlab::studies {

struct SeenTrial {
  int position = 0;        // the trial's place in the schedule (its random draws)
  double rate_hz = 120.0;  // frames a second, the display's and its own
  SeenHandGeometry hand;   // how the simulated hand looks
};

}  // namespace handlab::studies
