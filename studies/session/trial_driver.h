// What runs one trial for a session: its set-up in, its result out, each frame handed to a
// sink for the database. The session runner sees only this interface; PipelineTrialDriver is
// handlab's real pipeline: a rig built for the trial (trial_rig.h) run by the trial loop
// (trial_loop.h), the tracker (tracker.h) what drives it.
#pragma once

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"
#include "studies/session/tracker.h"
#include "studies/session/trial_display.h"
#include "studies/session/trial_loop.h"
#include "studies/session/trial_rig.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

class SessionControl;

class TrialDriver {
 public:
  virtual ~TrialDriver() = default;
  // Once per session, before the first trial: the tracker-to-scene calibration, for the
  // first condition's simulated hand.
  virtual retarget::Calibration calibrate(const Protocol& protocol,
                                          const store::Participant& participant) = 0;
  virtual TrialRun run(const TrialSetup& setup, const FrameSink& sink) = 0;
  // A front end's requests and observers (session_control.h); null: none.
  void attach(SessionControl* control) { control_ = control; }

 protected:
  SessionControl* control_ = nullptr;
};

class PipelineTrialDriver : public TrialDriver {
 public:
  // `sim_threads`: the soft-hand simulator's threads (1 when sessions run side by side).
  explicit PipelineTrialDriver(TrackerPtr tracker, double rate_hz = 120.0,
                               WorldKind world = WorldKind::kGraspProxy, int sim_threads = 2);
  // Steps at the rate in wall-clock time (the app) instead of as fast as the pipeline goes
  // (the CLI and simulated studies); a live tracker always does.
  void set_real_time(bool on) { real_time_ = on; }
  retarget::Calibration calibrate(const Protocol& protocol,
                                  const store::Participant& participant) override;
  TrialRun run(const TrialSetup& setup, const FrameSink& sink) override;

 private:
  TrackerPtr tracker_;
  double rate_hz_;
  bool real_time_ = false;
  TrialRigFactory rigs_;
};

}  // namespace handlab::studies
