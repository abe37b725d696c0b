// A whole simulated study: enrol N participants drawn from a population (their covariates
// stored like real ones, marked simulated) and run every session with the closed-loop
// participant model through the same session runner as a person's. Sessions run side by side,
// each in a database of its own, and are imported into the study's in enrolment order, so
// that the study's content depends on the seed alone (not on the threads or their timing).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "studies/analysis/condition_outcomes.h"
#include "studies/participant/activity_time.h"
#include "studies/participant/participant_model.h"
#include "studies/protocol/protocol.h"
#include "studies/session/trial_driver.h"

namespace handlab::studies {

struct SimulationOptions {
  int participants = 20;  // the study's size: participants S01 ... drawn in this order
  // A shard: the indices (0-based) of the participants to enrol and run here, each at its
  // place in the whole study's enrolment (empty: all). A participant's data depends on the
  // protocol, the seed, its index and the model alone, so that shards merged
  // (`handlab-cli merge`) equal the whole study run at once.
  std::vector<int> only;
  std::uint64_t seed = 0;  // the population's draws and every person's own stream
  int jobs = 1;            // sessions run at once (threads)
  WorldKind world = WorldKind::kSoftHand;
  bool frames = false;  // store every trial's frames (about 160 kB a simulated second)
  Population population;
  ParticipantModel model = frozen_participant_model();
};

struct SimulationReport {
  int participants = 0;                         // run here
  int trials = 0, completed = 0, timeouts = 0;  // every trial run, practice included
  std::vector<ConditionOutcome> conditions;     // in the protocol's order (scheduled trials)
  double seconds = 0.0;                         // wall-clock
  double simulated_seconds = 0.0;               // trial time simulated
  // The soft hand's steps per condition, in the protocol's order (practice included; all
  // zero on the grasp proxy): where the study's time went.
  std::vector<std::pair<std::string, sim::StepTotals>> simulator;
  // Where the participants' time went, by the cube they saw (m, smallest first; every trial,
  // practice included): pooled over what they can tell apart, never by condition.
  std::vector<std::pair<double, ActivityTime>> participant_time;
};

struct SimulationProgress {
  int participants_done = 0, participants = 0;
  int trials_done = 0, trials = 0;
  double seconds = 0.0;
};

// Creates the study database `db_path` (which must not exist) from `protocol`, enrols
// and runs (the participants of `options.only`, if given). `progress` is called from the calling
// thread after every trial of any session.
SimulationReport simulate_study(
    const Protocol& protocol, const std::string& db_path, const SimulationOptions& options,
    const std::function<void(const SimulationProgress&)>& progress = {});

}  // namespace handlab::studies
