// Where a trial's tracked hand comes from, frame by frame, in closed loop: given what the
// display showed after the last step, the tracked frame of the next. A simulated participant
// acts on what it saw; a script, a recording and a live tracker send their frames whatever it
// shows. The trial loop (trial_loop.h) reads every kind through this alone.
#pragma once

#include <chrono>
#include <optional>
#include <thread>

#include "core/tracking/tracked_frame.h"
#include "studies/participant/observation.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

class TrialFrameSource {
 public:
  using Clock = std::chrono::steady_clock;
  virtual ~TrialFrameSource() = default;

  // The frame of the next step, `shown` the display after the last (at 0 before the first);
  // nullopt: no hand this step.
  virtual std::optional<tracking::TrackedFrame> next(const Observation& shown) = 0;
  // Sends no more frames (a script or a recording played to its end).
  virtual bool ended() const { return false; }
  // Runs against the wall clock whatever the driver asks (a person at a live tracker).
  virtual bool live() const { return false; }
  // In real time, before the step due at `due` (steps `period` apart): waits for it.
  virtual void wait_for_step(Clock::time_point due, Clock::duration) {
    std::this_thread::sleep_until(due);
  }
  // What the trial's result carries of the source once it ends (a simulated participant's
  // account and memory).
  virtual void finish(TrialRun&) const {}
};

}  // namespace handlab::studies
