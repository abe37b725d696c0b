// The open-palm calibration as a person goes through it: the right hand held open and still
// over the scene for a few seconds, one tracked frame at a time. While no hand is seen, two
// hands are, the hand is closed or it moves, the step refuses with the reason and its
// countdown starts again. Then the scale comes from the held frames (calibrate_open_palm,
// core/retarget/retargeter.h) and the held palm is placed 12 cm above zone A, as a recording's
// median palm is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/hand/skeleton.h"
#include "core/retarget/retargeter.h"
#include "core/task/scene_layout.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::studies {

struct CalibrationStatus {
  enum class State { kNoHand, kTwoHands, kClosed, kMoving, kHolding, kDone };
  State state = State::kNoHand;
  double remaining_s = 0.0;                     // of the hold, while holding
  std::optional<retarget::Calibration> result;  // once done
  tracking::TrackedFrame frame;                 // the frame this status is about
  // What the experimenter and the participant read: the reason of a refusal, the countdown,
  // or the measured scale.
  std::string message() const;
};

struct OpenPalmSettings {
  double hold_s = 2.0;        // still and open for this long
  double max_speed = 0.05;    // m/s of the palm: faster is moving
  double max_grab = 0.1;      // Leap's grab strength: more is a closed hand
  double palm_height = 0.12;  // m above zone A where the held palm is placed
};

class OpenPalmCalibration {
 public:
  // `simulated`: the first condition's simulated hand; `hand_length`: the participant's (m).
  OpenPalmCalibration(const task::SceneLayout& scene, const hand::Skeleton& simulated,
                      double hand_length, OpenPalmSettings settings = {});
  const CalibrationStatus& feed(const tracking::TrackedFrame& frame);
  const CalibrationStatus& status() const { return status_; }
  bool done() const { return status_.state == CalibrationStatus::State::kDone; }

 private:
  void restart(CalibrationStatus::State why);

  task::SceneLayout scene_;
  const hand::Skeleton& simulated_;
  double hand_length_;
  OpenPalmSettings settings_;
  std::vector<tracking::TrackedFrame> held_;
  CalibrationStatus status_;
};

}  // namespace handlab::studies
