#include "core/retarget/recording_poses.h"

#include <stdexcept>

#include "core/hand/simulated_hand.h"
#include "core/tracking/hand_fitting.h"

namespace handlab::retarget {

RecordingPoses retarget_recording(const tracking::Recording& recording, Strategy strategy,
                                  hand::HandShape shape) {
  RecordingPoses out;
  auto fitter = tracking::TrackedHandFitter::for_recording(recording.frames, out.side);
  if (!fitter) {
    out.side = tracking::Side::kLeft;
    fitter = tracking::TrackedHandFitter::for_recording(recording.frames, out.side);
  }
  if (!fitter) throw std::runtime_error(recording.source + ": no hand in the recording");
  shape.left = out.side == tracking::Side::kLeft;
  out.shape = shape;
  out.skeleton = hand::build_simulated_hand(shape);
  auto calibration = calibrate_open_palm(recording.frames, out.side, out.skeleton, *fitter);
  if (!calibration) {  // no open hand: the ratio of hand lengths, as `retarget` does
    calibration = Calibration{};
    calibration->scale = shape.length / *tracking::estimate_hand_length(recording.frames, out.side);
  }
  Retargeter retargeter(strategy, out.skeleton, *calibration,
                        strategy == Strategy::kNaive ? fitter : std::nullopt);
  for (const tracking::TrackedFrame& frame : recording.frames)
    if (const tracking::TrackedHand* h = frame.hand(out.side)) {
      out.poses.push_back(retargeter.retarget(*h).pose);
      out.times.push_back(frame.timestamp);
    }
  return out;
}

}  // namespace handlab::retarget
