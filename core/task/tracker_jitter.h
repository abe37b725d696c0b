// A tracker's jitter, taken from a real recording to lay on a scripted closing: the
// intermediate hand's poses retargeted from the recording less their moving average over a
// window (what the hand itself does more slowly than that), as offsets in time.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"

namespace handlab::sim {

struct PoseJitter {
  std::vector<double> times;            // s from the first frame
  std::vector<Eigen::VectorXd> angles;  // rad, per DOF
  std::vector<Eigen::Vector3d> root;    // m, the wrist's position
  std::vector<Eigen::Vector3d> turn;    // rad, the wrist's rotation vector

  double duration() const { return times.empty() ? 0.0 : times.back(); }
  // RMS of the root's offsets per axis (m) and of the angles' (rad, over every DOF).
  double root_rms() const;
  double angle_rms() const;
  // Adds `scale` times the offsets of the frame at time t (the recording looped) to `pose`;
  // throws std::invalid_argument for a pose of another number of angles.
  void apply(double t, double scale, hand::HandPose& pose) const;
};

// The jitter of `poses` at `times` (s, increasing): each pose less the mean of the poses within
// half a `window` (s) either side, where the window is whole (the first and last half window
// left out). Throws std::invalid_argument when fewer than two poses are left.
PoseJitter pose_jitter(const std::vector<double>& times, const std::vector<hand::HandPose>& poses,
                       double window = 0.1);

}  // namespace handlab::sim
