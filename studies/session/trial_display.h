// What the display shows a participant and what a person knows of a trial before it starts:
// the one place where a trial is reduced to what is seen (SimulatedParticipantBlinding).
#pragma once

#include "core/task/hand_cube_world.h"
#include "core/task/scene_layout.h"
#include "studies/participant/observation.h"
#include "studies/participant/seen_trial.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

// What the display shows after a step at `time`: the simulated hand, the cube, the zones
// (a simulated participant's only input).
Observation display_observation(const task::HandCubeWorld& world, const task::SceneLayout& layout,
                                double time);

// What a person can know of a trial before it starts: its place in the schedule and how the
// simulated hand looks; the simulated participant is built from this alone.
SeenTrial seen_trial_of(const TrialSetup& setup, double rate_hz);

}  // namespace handlab::studies
