// Fitting tracked frames with the tracked-hand skeleton of the hand-models module, so that
// the rest of the pipeline sees one consistent skeleton whose bone lengths do not jitter.
#pragma once

#include <optional>
#include <vector>

#include "core/hand/fit_workspace.h"
#include "core/hand/tracked_hand.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::tracking {

// The person's hand length from a recording: the median over frames of the middle finger's
// mcp-pip-dip-tip path, divided by its share of hand length (0.544, Buchholz et al. 1992).
// nullopt when no frame has a hand of that side.
std::optional<double> estimate_hand_length(const std::vector<TrackedFrame>& frames, Side side);

hand::LeapJoints leap_joints(const TrackedHand& hand);
// A tracked hand with the given joints (e.g. a skeleton's pose written as a frame).
TrackedHand tracked_hand(const hand::LeapJoints& joints, Side side, std::int32_t id = 1);

// The person's skeleton measured from a recording: medians over frames of every phalanx
// length and of the mcp (and, where the source has them, carp) positions in the palm's
// frame. nullopt when no frame has a hand of that side.
std::optional<hand::MeasuredSkeleton> measure_skeleton(const std::vector<TrackedFrame>& frames,
                                                       Side side, double hand_length);

// Fits one hand per call, each fit starting from the previous one's pose.
class TrackedHandFitter {
 public:
  TrackedHandFitter(double hand_length, Side side,
                    const hand::MeasuredSkeleton* measured = nullptr);
  // The skeleton measured from the frames of `side` in a recording.
  static std::optional<TrackedHandFitter> for_recording(const std::vector<TrackedFrame>& frames,
                                                        Side side);
  hand::FitResult fit(const TrackedHand& hand);
  const hand::Skeleton& skeleton() const { return skeleton_; }
  void reset() { previous_.reset(); }

 private:
  hand::Skeleton skeleton_;
  hand::FitWorkspace workspace_;
  std::optional<hand::HandPose> previous_;
};

}  // namespace handlab::tracking
