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

// Bones: palm; then per digit metacarpal, proximal, intermediate, distal (17 bones).
// Markers "<digit>_carp", "_mcp", "_pip", "_dip", "_tip".
Skeleton build_tracked_hand(const HandShape& shape);

LeapJoints to_leap_joints(const Skeleton& tracked, const HandPose& pose);

struct FitResult {
  HandPose pose;
  double rms_residual;  // over the 25 joint positions (m)
  double max_residual;  // (m)
  int iterations;
};

// Least-squares fit of the skeleton's pose to a frame's 25 joint positions (damped
// Gauss-Newton from the palm frame, joint angles kept within their limits).
FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          int max_iterations = 30);

// The palm centre's place in the tracked skeleton's root (wrist) frame.
Eigen::Vector3d palm_centre_offset(const HandShape& shape);

}  // namespace handlab::hand
