// What runs one trial: tracker -> retargeting -> hand-cube physics -> task, one frame at a
// time, each frame handed to a sink for the database. The session runner sees only this
// interface; PipelineTrialDriver is handlab's real pipeline.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/retarget/retargeter.h"
#include "core/sim/step_totals.h"
#include "core/store/frame_record.h"
#include "core/store/study_store.h"
#include "core/task/hand_cube_world.h"
#include "core/task/scene_layout.h"
#include "core/tracking/frame_source.h"
#include "studies/participant/activity_time.h"
#include "studies/participant/observation.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/seen_trial.h"
#include "studies/participant/trial_experience.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

class SessionControl;

struct TrialSetup {
  const Protocol* protocol = nullptr;
  Condition condition;
  store::Participant participant;
  store::PlannedTrialRow planned;
  retarget::Calibration calibration;
  // A simulated participant's memory from its earlier trials (JSON; empty before its first).
  std::string participant_memory;
};

struct TrialRun {
  bool success = false;
  double completion_time_s = 0.0;
  int grasps = 0, drops = 0;
  long frames = 0;
  std::vector<std::pair<double, std::string>> events;
  // A simulated participant's account of the trial (its questionnaire answers come from it),
  // and what it carries to its next trial (JSON).
  std::optional<TrialExperience> experience;
  std::string participant_memory;
  // Stopped by the experimenter before its end (SessionControl::request_stop): no result.
  bool aborted = false;
  // What the soft hand's simulator steps cost in the trial (none on the grasp proxy).
  sim::StepTotals simulator;
};

// Thrown by a calibration that a stop request ended.
struct SessionStopped : std::runtime_error {
  SessionStopped() : std::runtime_error("the session was stopped") {}
};

using FrameSink = std::function<void(const store::FrameRecord&)>;

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

// Where the pipeline's frames come from: the built-in scripted (open-loop) participant, a
// recording replayed at the simulation rate for every trial, a simulated participant who
// sees the display and acts in closed loop (docs/simulated-participants.md), its parameters
// drawn from the population under `seed` and the participant's id, or a live tracker.
class TrackerKind {
 public:
  // A live tracker (app/live: the Leap over its WebSocket): `open` gives its source. The
  // session runs in real time, each step taken as soon as a frame arrives (at most one step
  // ahead of the clock); the participant calibrates with an open palm.
  using LiveOpener = std::function<std::unique_ptr<tracking::LiveFrameSource>()>;
  static TrackerKind live(std::string name, LiveOpener open) {
    TrackerKind k(Kind::kLive, std::move(name), 0);
    k.open_live_ = std::move(open);
    return k;
  }
  bool is_live() const { return kind_ == Kind::kLive; }
  std::unique_ptr<tracking::LiveFrameSource> open_live() const { return open_live_(); }
  static TrackerKind scripted() { return TrackerKind(Kind::kScripted, "", 0); }
  static TrackerKind recording(std::string path) {
    return TrackerKind(Kind::kRecording, std::move(path), 0);
  }
  // Simulated participants of the population under `seed`, of `model` (the frozen one unless
  // a sensitivity analysis changes it).
  static TrackerKind simulated(std::uint64_t seed,
                               const ParticipantModel& model = frozen_participant_model()) {
    TrackerKind k(Kind::kSimulated, "", seed);
    k.model_ = std::make_shared<const ParticipantModel>(model);
    return k;
  }
  bool is_scripted() const { return kind_ == Kind::kScripted; }
  bool is_simulated() const { return kind_ == Kind::kSimulated; }
  bool is_recording() const { return kind_ == Kind::kRecording; }
  const std::string& path() const { return path_; }
  std::uint64_t seed() const { return seed_; }
  const ParticipantModel& participant_model() const {
    return model_ ? *model_ : frozen_participant_model();
  }
  std::string name() const;

 private:
  enum class Kind { kScripted, kRecording, kSimulated, kLive };
  TrackerKind(Kind kind, std::string path, std::uint64_t seed)
      : kind_(kind), path_(std::move(path)), seed_(seed) {}
  Kind kind_;
  std::string path_;
  std::uint64_t seed_;
  LiveOpener open_live_;
  std::shared_ptr<const ParticipantModel> model_;
};

// The hand-cube physics a trial runs on: the grasp proxy (the cube attaches to a pinch,
// core/task/grasp_proxy.h) or the soft-hand simulator (contact and friction only,
// core/task/soft_hand_world.h, docs/simulator.md).
enum class WorldKind { kGraspProxy, kSoftHand };

class OwnHand;
class SimulatedParticipant;

// What the display shows after a step at `time`: the simulated hand, the cube, the zones
// (a simulated participant's only input).
Observation display_observation(const task::HandCubeWorld& world, const task::SceneLayout& layout,
                                double time);

// What a person can know of a trial before it starts: its place in the schedule and how the
// simulated hand looks. The one place where a trial's condition is reduced to what is seen;
// the simulated participant is built from this alone (SimulatedParticipantBlinding).
SeenTrial seen_trial_of(const TrialSetup& setup, double rate_hz);

class PipelineTrialDriver : public TrialDriver {
 public:
  // `sim_threads`: the soft-hand simulator's threads (1 when sessions run side by side).
  explicit PipelineTrialDriver(TrackerKind tracker, double rate_hz = 120.0,
                               WorldKind world = WorldKind::kGraspProxy, int sim_threads = 2);
  ~PipelineTrialDriver() override;
  // Steps at the rate in wall-clock time (the app; always with a live tracker) instead of as
  // fast as the pipeline goes (the CLI and simulated studies).
  void set_real_time(bool on) { real_time_ = on; }
  retarget::Calibration calibrate(const Protocol& protocol,
                                  const store::Participant& participant) override;
  TrialRun run(const TrialSetup& setup, const FrameSink& sink) override;
  // The soft hand's steps of every trial run so far, per condition label.
  const std::map<std::string, sim::StepTotals>& simulator_totals() const {
    return simulator_totals_;
  }
  // Where the simulated participants' time went in every trial run so far to its result (not
  // those stopped by the experimenter), by the cube they saw (its side in m, to the millimetre).
  const std::map<double, ActivityTime>& participant_time() const { return participant_time_; }

 private:
  // The simulated participant of a trial: from who it is, what it sees of the trial and what
  // it remembers; nothing of the condition is in scope here.
  std::unique_ptr<SimulatedParticipant> simulated_participant(const store::Participant& person,
                                                              const SeenTrial& trial,
                                                              const std::string& memory);
  // `simulated` is the condition's simulated hand (the scripted pinch closes on its tips).
  std::unique_ptr<tracking::FrameSource> open_tracker(const TrialSetup& setup,
                                                      const hand::Skeleton& simulated) const;

  TrackerKind tracker_;
  double rate_hz_;
  WorldKind world_;
  int sim_threads_;
  bool real_time_ = false;
  std::unique_ptr<OwnHand> own_hand_;  // the simulated participant's, built once per size
  double own_hand_length_ = 0.0;
  std::vector<tracking::TrackedFrame> recording_;  // loaded once
  struct SoftHand;  // the soft hand's flesh and model for a simulated hand and cube
  std::vector<std::unique_ptr<SoftHand>> soft_hands_;  // built once each, kept
  std::map<std::string, sim::StepTotals> simulator_totals_;
  std::map<double, ActivityTime> participant_time_;
};

}  // namespace handlab::studies
