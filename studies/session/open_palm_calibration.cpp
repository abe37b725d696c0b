#include "studies/session/open_palm_calibration.h"

#include <cstdio>

namespace handlab::studies {

std::string CalibrationStatus::message() const {
  char text[160];
  switch (state) {
    case State::kNoHand:
      return "No hand seen: hold your right hand open over the table.";
    case State::kTwoHands:
      return "Two hands seen: hold up your right hand only.";
    case State::kClosed:
      return "The hand is closed: open it, fingers spread and flat.";
    case State::kMoving:
      return "The hand moves: hold it still.";
    case State::kHolding:
      std::snprintf(text, sizeof text, "Hold still: %.1f s", remaining_s);
      return text;
    case State::kDone:
      std::snprintf(text, sizeof text, "Calibrated: scale %.3f", result ? result->scale : 0.0);
      return text;
  }
  return {};
}

OpenPalmCalibration::OpenPalmCalibration(const task::SceneLayout& scene,
                                         const hand::Skeleton& simulated, double hand_length,
                                         OpenPalmSettings settings)
    : scene_(scene), simulated_(simulated), hand_length_(hand_length), settings_(settings) {}

void OpenPalmCalibration::restart(CalibrationStatus::State why) {
  held_.clear();
  status_.state = why;
  status_.remaining_s = settings_.hold_s;
}

const CalibrationStatus& OpenPalmCalibration::feed(const tracking::TrackedFrame& frame) {
  if (done()) return status_;
  status_.frame = frame;
  const tracking::TrackedHand* hand = frame.hand(tracking::Side::kRight);
  if (frame.hands.size() > 1) {
    restart(CalibrationStatus::State::kTwoHands);
  } else if (!hand) {
    restart(CalibrationStatus::State::kNoHand);
  } else if (hand->grab_strength > settings_.max_grab) {
    restart(CalibrationStatus::State::kClosed);
  } else {
    if (!held_.empty()) {
      const tracking::TrackedFrame& last = held_.back();
      const double dt = frame.timestamp - last.timestamp;
      const tracking::TrackedHand* before = last.hand(tracking::Side::kRight);
      if (dt > 0 &&
          (hand->palm_position - before->palm_position).norm() / dt > settings_.max_speed) {
        restart(CalibrationStatus::State::kMoving);
        return status_;
      }
      if (dt <= 0) return status_;  // the same frame again: nothing new
    }
    held_.push_back(frame);
    const double held_for = frame.timestamp - held_.front().timestamp;
    status_.state = CalibrationStatus::State::kHolding;
    status_.remaining_s = std::max(0.0, settings_.hold_s - held_for);
    if (held_for >= settings_.hold_s) {
      auto calibration = retarget::calibrate_open_palm(
          held_, tracking::Side::kRight, simulated_,
          tracking::TrackedHandFitter(hand_length_, tracking::Side::kRight));
      if (!calibration) {
        restart(CalibrationStatus::State::kClosed);
        return status_;
      }
      Eigen::Vector3d palm = Eigen::Vector3d::Zero();
      for (const auto& f : held_) palm += f.hand(tracking::Side::kRight)->palm_position;
      palm /= double(held_.size());
      calibration->tracker_to_scene =
          Eigen::Translation3d(scene_.zone_a + Eigen::Vector3d(0, settings_.palm_height, 0) - palm);
      status_.state = CalibrationStatus::State::kDone;
      status_.remaining_s = 0.0;
      status_.result = calibration;
    }
  }
  return status_;
}

}  // namespace handlab::studies
