// The tracked hand in the Leap Motion's skeletal morphology: a palm and, per digit, a
// metacarpal from the carpus (carp) to the MCP and three phalanges (mcp-pip, pip-dip,
// dip-tip); the thumb's metacarpal has zero length (carp = mcp), as the Leap service reports
// it, so its "proximal" bone is the anatomical metacarpal. Sized by the person's hand length.
// Conversion to and from the joint positions of a Leap frame, and fitting a frame.
#pragma once

#include <array>

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"

namespace handlab::hand {

// The joint positions a Leap frame reports for one hand (metres, one frame of reference).
struct LeapJoints {
  // joints[digit][k], k = 0 carp, 1 mcp, 2 pip, 3 dip, 4 tip; digits thumb..pinky.
  std::array<std::array<Eigen::Vector3d, 5>, kFingerCount> joints;
  Eigen::Vector3d palm_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d palm_normal = Eigen::Vector3d::UnitZ();  // out of the palm
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();    // palm towards the fingers
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();
};

// A person's skeleton measured from tracked frames (see tracking/hand_fitting.h): per digit
// the carp and mcp positions in the wrist frame (+x radial, +y distal, +z palmar) and the
// three phalanx lengths.
struct MeasuredSkeleton {
  std::array<Eigen::Vector3d, kFingerCount> carp, mcp;
  std::array<std::array<double, 3>, kFingerCount> lengths;
};

// Bones: palm; then per digit metacarpal, proximal, intermediate, distal (21 bones).
// Markers "<digit>_carp", "_mcp", "_pip", "_dip", "_tip", "palm_centre". Proportions from
// the shape's anthropometric table, or measured ones when given.
Skeleton build_tracked_hand(const HandShape& shape, const MeasuredSkeleton* measured = nullptr);

// The markers of a Leap frame's 25 joints (digit * 5 + k, k = carp, mcp, pip, dip, tip) and,
// last, the palm centre.
std::array<int, 26> leap_joint_markers(const Skeleton& tracked);

LeapJoints to_leap_joints(const Skeleton& tracked, const HandPose& pose);

struct FitResult {
  HandPose pose;
  double rms_residual;  // over the 25 joint positions (m)
  double max_residual;  // (m)
  int iterations;
};

struct FitOptions {
  int max_iterations = 30;
  // Per joint (digit * 5 + k) weight of its residual; 0 leaves a joint out (e.g. a carp
  // position the source did not have).
  std::array<double, 25> weights = uniform_weights();
  // Start from this pose (the previous frame's) instead of the reported palm frame.
  const HandPose* initial = nullptr;
  static std::array<double, 25> uniform_weights() {
    std::array<double, 25> w;
    w.fill(1.0);
    return w;
  }
};

struct FitWorkspace;  // fit_workspace.h

// Weighted least-squares fit of the skeleton's pose to a frame's 25 joint positions (damped
// Gauss-Newton, joint angles kept within their limits).
FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          const FitOptions& options);
// The same in a workspace made for `tracked`, kept from frame to frame (no allocation but the
// result's pose).
FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          const FitOptions& options, FitWorkspace& workspace);
FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          int max_iterations = 30);

// The palm centre's place in the tracked skeleton's root (wrist) frame.
Eigen::Vector3d palm_centre_offset(const HandShape& shape);

}  // namespace handlab::hand
