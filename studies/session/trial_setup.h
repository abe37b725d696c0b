// A trial as the session hands it to a driver (TrialSetup) and what comes back (TrialRun).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/retarget/retargeter.h"
#include "core/sim/step_totals.h"
#include "core/store/study_store.h"
#include "core/task/scene_layout.h"
#include "studies/participant/trial_experience.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

struct TrialSetup {
  const Protocol* protocol = nullptr;
  Condition condition;
  store::Participant participant;
  store::PlannedTrialRow planned;
  retarget::Calibration calibration;
  // A simulated participant's memory from its earlier trials (JSON; empty before its first).
  std::string participant_memory;
};

// The scene of the trial: the protocol's, with the condition's cube.
task::SceneLayout trial_layout(const TrialSetup& setup);

struct TrialRun {
  bool success = false;
  double completion_time_s = 0.0;
  int grasps = 0, drops = 0;
  long frames = 0;
  std::vector<std::pair<double, std::string>> events;
  // A simulated participant's account of the trial (its questionnaire answers and the time it
  // spent come from it), and what it carries to its next trial (JSON).
  std::optional<TrialExperience> experience;
  std::string participant_memory;
  // Stopped by the experimenter before its end (SessionControl::request_stop): no result.
  bool aborted = false;
  std::string abort_reason;  // why, where not the experimenter's stop
  // What the soft hand's simulator steps cost in the trial (none on the grasp proxy).
  sim::StepTotals simulator;
};

// Thrown by a calibration that a stop request ended.
struct SessionStopped : std::runtime_error {
  SessionStopped() : std::runtime_error("the session was stopped") {}
};

}  // namespace handlab::studies
