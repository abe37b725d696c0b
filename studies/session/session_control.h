// How a front end steers a running session from its own thread, and what it sees of it.
// The session thread (SessionRunner, PipelineTrialDriver) polls the requests and calls the
// observers; the app and the CLI share the runner, so pausing, stopping, redoing and
// skipping mean the same in both.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/store/frame_record.h"
#include "core/task/cube_task.h"
#include "core/tracking/tracked_frame.h"
#include "studies/session/open_palm_calibration.h"

namespace handlab::hand {
struct HandFlesh;
}

namespace handlab::studies {

struct TrialSetup;
struct TrialRun;

// The state after one simulation step of a trial.
struct TrialStep {
  double time = 0.0;  // s since the trial started
  task::TaskPhase phase = task::TaskPhase::kReady;
  int grasps = 0, drops = 0;
  const store::FrameRecord* frame = nullptr;  // what the frame log stores of this step
  // On the soft hand, its flesh and where the flesh's nodes are after this step, for a front
  // end to draw the skin the participant sees (the frame log keeps only the bones); null on
  // the grasp proxy and before the hand appears. Like `frame`, valid during the call only.
  const hand::HandFlesh* flesh = nullptr;
  const std::vector<Eigen::Vector3d>* flesh_nodes = nullptr;
};

// An experimenter's decision about a trial, with the reason kept in the record.
struct TrialDecision {
  enum class Kind { kRedo, kSkip } kind = Kind::kRedo;
  int position = 0;  // 0-based place in the schedule
  std::string reason;
};

class SessionControl {
 public:
  // --- Requests, from any thread.
  // While paused, the session holds before the next trial starts (a trial under way runs to
  // its end: a timed trial cannot be frozen without changing what it measures).
  void set_paused(bool paused);
  bool paused() const { return paused_; }
  // Ends the session: a trial under way is aborted (kept, with the reason; it runs again
  // when the session resumes), a calibration under way gives up.
  void request_stop();
  bool stop_requested() const { return stop_; }
  // Applied by the session thread between trials, in the order given.
  void decide(TrialDecision decision);

  // --- The session thread's side.
  // Waits while paused; false once a stop is requested.
  bool hold_while_paused();
  std::vector<TrialDecision> take_decisions();

  // --- Observers, set before the session starts; called on the session thread.
  std::function<void(const CalibrationStatus&)> calibration;
  std::function<void(const TrialSetup&, int planned_trials)> trial_started;
  std::function<void(const TrialStep&)> stepped;
  std::function<void(const TrialSetup&, const TrialRun&)> trial_ended;
  // A decision was applied (error empty) or refused by the store (its message).
  std::function<void(const TrialDecision&, const std::string& error)> decided;
  std::function<void()> holding;  // the session waits because it is paused

 private:
  std::atomic<bool> paused_{false}, stop_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<TrialDecision> decisions_;
};

}  // namespace handlab::studies
