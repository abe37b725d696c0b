// What drives a session's trials: the built-in scripted (open-loop) participant, a recording
// replayed at the simulation rate for every trial, a simulated participant who sees the
// display and acts in closed loop (docs/simulated-participants.md), or a live tracker. One
// interface; what differs between them lives in their own files (scripted_source.cpp,
// recording_source.cpp, simulated_source.cpp, live_source.cpp), so no code asks which kind a
// tracker is. A tracker is immutable and shared between the sessions run side by side; what
// its sources keep between one driver's trials is in that driver's TrialCache.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/hand/skeleton.h"
#include "core/retarget/retargeter.h"
#include "core/tracking/frame_source.h"
#include "core/tracking/hand_fitting.h"
#include "studies/participant/participant_model.h"
#include "studies/protocol/protocol.h"
#include "studies/session/questionnaire_responder.h"
#include "studies/session/trial_frame_source.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

class OwnHand;
class SessionControl;

// What a tracker's sources keep between one driver's trials (one thread): the simulated
// participant's own hand, built once a length and shared with the sources that use it.
class TrialCache {
 public:
  TrialCache();
  ~TrialCache();
  std::shared_ptr<const OwnHand> own_hand(double hand_length);

 private:
  std::shared_ptr<const OwnHand> own_hand_;
  double own_hand_length_ = 0.0;
};

class Tracker {
 public:
  virtual ~Tracker() = default;
  virtual std::string name() const = 0;
  // Once a session: the tracker-to-scene calibration for `first_hand` (the first condition's
  // simulated hand); its progress and outcome to `control` (may be null).
  virtual retarget::Calibration calibrate(const Protocol& protocol,
                                          const store::Participant& participant,
                                          const hand::Skeleton& first_hand,
                                          SessionControl* control) const = 0;
  // How Naive reads the tracked hand's size.
  virtual std::optional<tracking::TrackedHandFitter> fitter(
      const store::Participant& participant) const;
  // The trial's frames; `simulated` is the condition's hand.
  virtual std::unique_ptr<TrialFrameSource> open(const TrialSetup& setup,
                                                 const hand::Skeleton& simulated, double rate_hz,
                                                 TrialCache& cache) const = 0;
  // Who answers the questionnaires when the tracker is a person of its own (a simulated one).
  virtual std::optional<QuestionnaireResponder> own_answers() const { return std::nullopt; }
};

using TrackerPtr = std::shared_ptr<const Tracker>;

TrackerPtr scripted_tracker();
TrackerPtr recording_tracker(const std::string& path);
// Simulated participants of the population under `seed`, of `model` (the frozen one unless a
// sensitivity analysis changes it), their parameters drawn from the seed and their ids.
TrackerPtr simulated_tracker(std::uint64_t seed,
                             const ParticipantModel& model = frozen_participant_model());
// A live tracker (app/live: the Leap over its WebSocket): `open` gives its source. The
// session runs in real time, each step taken as soon as a frame arrives (at most one step
// ahead of the clock); the participant calibrates with an open palm.
using LiveOpener = std::function<std::unique_ptr<tracking::LiveFrameSource>()>;
TrackerPtr live_tracker(std::string name, LiveOpener open);

// What a front end shows when a calibration is done: the outcome and the frame it came from.
void report_calibration(SessionControl* control, const retarget::Calibration& calibration,
                        tracking::TrackedFrame frame);

}  // namespace handlab::studies
