// A whole recording retargeted onto a simulated hand, as `sim replay` plays it and the grasp
// map takes its tracker's jitter: the hand the recording holds (its right, else its left),
// calibrated on an open palm (else by the ratio of hand lengths), each frame's pose.
#pragma once

#include <vector>

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/retarget/retargeter.h"
#include "core/tracking/recording_io.h"

namespace handlab::retarget {

struct RecordingPoses {
  tracking::Side side = tracking::Side::kRight;
  hand::HandShape shape;      // `shape`, mirrored for a left hand
  hand::Skeleton skeleton;    // the simulated hand of `shape`
  std::vector<double> times;  // s, the frames' timestamps
  std::vector<hand::HandPose> poses;
};

// Throws std::runtime_error when the recording holds no hand.
RecordingPoses retarget_recording(const tracking::Recording& recording, Strategy strategy,
                                  hand::HandShape shape = {});

}  // namespace handlab::retarget
