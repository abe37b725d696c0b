// One trial run step by step on its rig: the source's frame -> retargeting -> the world's step
// -> the task -> the frame record -> what the display shows, which the source sees next.
#pragma once

#include <functional>

#include "core/store/frame_record.h"
#include "studies/session/trial_rig.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

class SessionControl;

using FrameSink = std::function<void(const store::FrameRecord&)>;

struct TrialLoopOptions {
  double rate_hz = 120.0;
  // Steps at the rate in wall-clock time (the app) instead of as fast as the pipeline goes;
  // a live source always does.
  bool real_time = false;
  SessionControl* control = nullptr;  // a front end's requests and observers; null: none
};

// Runs `rig` until its task ends (or a stop request aborts it), each step's record to `sink`.
TrialRun run_trial(TrialRig& rig, const FrameSink& sink, const TrialLoopOptions& options);

}  // namespace handlab::studies
