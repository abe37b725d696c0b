#include "studies/session/tracker.h"

#include "studies/participant/own_hand.h"
#include "studies/session/session_control.h"

namespace handlab::studies {

TrialCache::TrialCache() = default;
TrialCache::~TrialCache() = default;

std::shared_ptr<const OwnHand> TrialCache::own_hand(double hand_length) {
  if (!own_hand_ || own_hand_length_ != hand_length) {
    own_hand_ = std::make_shared<const OwnHand>(hand_length);
    own_hand_length_ = hand_length;
  }
  return own_hand_;
}

std::optional<tracking::TrackedHandFitter> Tracker::fitter(
    const store::Participant& participant) const {
  return tracking::TrackedHandFitter(participant.hand_length, tracking::Side::kRight);
}

void report_calibration(SessionControl* control, const retarget::Calibration& calibration,
                        tracking::TrackedFrame frame) {
  if (!control || !control->calibration) return;
  CalibrationStatus status;
  status.state = CalibrationStatus::State::kDone;
  status.result = calibration;
  status.frame = std::move(frame);
  control->calibration(status);
}

}  // namespace handlab::studies
