// What runs one trial: tracker -> retargeting -> hand-cube physics -> task, one frame at a
// time, each frame handed to a sink for the database. The session runner sees only this
// interface; PipelineTrialDriver is handlab's real pipeline.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/retarget/retargeter.h"
#include "core/store/frame_record.h"
#include "core/store/study_store.h"
#include "core/tracking/frame_source.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

struct TrialSetup {
  const Protocol* protocol = nullptr;
  Condition condition;
  store::Participant participant;
  store::PlannedTrialRow planned;
  retarget::Calibration calibration;
};

struct TrialRun {
  bool success = false;
  double completion_time_s = 0.0;
  int grasps = 0, drops = 0;
  long frames = 0;
  std::vector<std::pair<double, std::string>> events;
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
};

// Where the pipeline's frames come from: the built-in scripted participant, or a recording
// replayed at the simulation rate for every trial.
class TrackerKind {
 public:
  static TrackerKind scripted() { return TrackerKind(""); }
  static TrackerKind recording(std::string path) { return TrackerKind(std::move(path)); }
  bool is_scripted() const { return path_.empty(); }
  const std::string& path() const { return path_; }
  std::string name() const { return is_scripted() ? "scripted" : path_; }

 private:
  explicit TrackerKind(std::string path) : path_(std::move(path)) {}
  std::string path_;
};

// The hand-cube physics a trial runs on: the grasp proxy (the cube attaches to a pinch,
// core/task/grasp_proxy.h) or the soft-hand simulator (contact and friction only,
// core/task/soft_hand_world.h, docs/simulator.md).
enum class WorldKind { kGraspProxy, kSoftHand };

class PipelineTrialDriver : public TrialDriver {
 public:
  explicit PipelineTrialDriver(TrackerKind tracker, double rate_hz = 120.0,
                               WorldKind world = WorldKind::kGraspProxy);
  ~PipelineTrialDriver() override;
  retarget::Calibration calibrate(const Protocol& protocol,
                                  const store::Participant& participant) override;
  TrialRun run(const TrialSetup& setup, const FrameSink& sink) override;

 private:
  // `simulated` is the condition's simulated hand (the scripted pinch closes on its tips).
  std::unique_ptr<tracking::FrameSource> open_tracker(const TrialSetup& setup,
                                                      const hand::Skeleton& simulated) const;

  TrackerKind tracker_;
  double rate_hz_;
  WorldKind world_;
  std::vector<tracking::TrackedFrame> recording_;  // loaded once
  struct SoftHand;  // the soft hand's flesh and model for a simulated hand and cube
  std::vector<std::unique_ptr<SoftHand>> soft_hands_;  // built once each, kept
};

}  // namespace handlab::studies
