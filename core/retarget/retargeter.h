// Pose retargeting: from a tracked hand (Leap morphology, the participant's size) to the
// intermediate hand (the simulated hand's morphology and size) that the simulation follows.
// Two strategies behind one interface: Naive (palms aligned on the four finger bases, joint
// angles copied) and Ours (uniform scale, then the fingertips fitted under joint limits).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/retarget/fingertip_solver.h"
#include "core/tracking/hand_fitting.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::retarget {

enum class Strategy { kNaive, kOurs };

struct Calibration {
  double scale = 1.0;  // simulated hand size / tracked hand size
  Eigen::Isometry3d tracker_to_scene = Eigen::Isometry3d::Identity();
};

// Uniform scale from an open palm: over frames where the hand is open (grab strength below
// 0.1), the bounding boxes in the palm plane of the tracked joints (mcp..tip of every digit)
// and of the simulated hand's corresponding joints in the same pose (the tracked skeleton's
// fitted joint angles copied onto it); the scale is the median ratio of the boxes'
// diagonals. nullopt without an open-hand frame.
std::optional<Calibration> calibrate_open_palm(const std::vector<tracking::TrackedFrame>& frames,
                                               tracking::Side side, const hand::Skeleton& simulated,
                                               tracking::TrackedHandFitter fitter);

struct RetargetResult {
  hand::HandPose pose;                     // the intermediate hand
  std::array<Eigen::Vector3d, 5> targets;  // scaled tracked fingertips, scene frame
  int iterations = 0;
};

// What Ours lets a study change: how much each fingertip counts (thumb first; thumb and
// index carry the pinch) and the fingertip solver's regularisers and iteration limits (its
// root translation weight is the retargeter's own).
struct OursOptions {
  std::array<double, 5> tip_weights = {4.0, 4.0, 1.0, 1.0, 1.0};
  SolverOptions solver;
};

class Retargeter {
 public:
  // `simulated` must outlive the retargeter. Naive needs the tracked skeleton's fit of each
  // frame, so it takes a fitter measured for the participant; Naive ignores `ours`.
  Retargeter(Strategy strategy, const hand::Skeleton& simulated, Calibration calibration,
             std::optional<tracking::TrackedHandFitter> fitter = std::nullopt,
             OursOptions ours = {});

  RetargetResult retarget(const tracking::TrackedHand& hand);
  Strategy strategy() const { return strategy_; }
  void reset() { previous_.reset(); }

 private:
  Strategy strategy_;
  const hand::Skeleton& simulated_;
  Calibration calibration_;
  std::optional<tracking::TrackedHandFitter> fitter_;
  std::unique_ptr<FingertipSolver> solver_;      // palm fixed on the finger bases
  std::unique_ptr<FingertipSolver> free_wrist_;  // palm free to shift, when tips are out of reach
  std::array<int, 4> mcp_markers_;
  std::array<Eigen::Vector3d, 4>
      mcp_in_palm_;  // the four finger bases in the rest pose, root frame
  std::array<int, 5> tip_markers_;
  std::optional<SolverResult> previous_;
};

}  // namespace handlab::retarget
