// A stored trial shown again: the frames its session logged (core/store/frame_logger.h), with
// the scene and the simulated hand of its condition, so that a front end can play it back or
// draw any moment of it (the app's Replay, `handlab-cli render --trial`). The log keeps the
// simulated hand's bones, not its flesh: a replay on the soft hand shows the bones.
#pragma once

#include <string>
#include <vector>

#include "core/hand/hand_shape.h"
#include "core/store/frame_record.h"
#include "core/store/study_store.h"
#include "core/task/scene_layout.h"

namespace handlab::studies {

struct TrialReplay {
  std::string participant;
  int position = 0;  // 0-based place in the schedule
  int attempt = 0;
  store::TrialStatus status = store::TrialStatus::kRunning;
  std::string condition;                   // its label, e.g. "naive-fine"
  task::SceneLayout layout;                // the protocol's scene with the condition's cube
  hand::HandShape simulated_hand;          // the condition's
  std::vector<store::FrameRecord> frames;  // in the order they were logged

  double duration() const { return frames.empty() ? 0.0 : frames.back().time; }
  // The frame on screen at `time` (s since the trial started): the last one logged at or
  // before it (the first before the first).
  const store::FrameRecord& frame_at(double time) const;
};

// The trial at `position` (0-based) of the participant's schedule, its attempt `attempt` (0:
// the latest attempt that logged frames). Throws std::runtime_error saying what is missing
// (no such participant or trial, or no frames: the trial never ran, was skipped, or ran in a
// simulated study run without --frames).
TrialReplay load_trial_replay(store::StudyStore& store, const std::string& participant,
                              int position, int attempt = 0);

}  // namespace handlab::studies
