// What a fit of Leap joints keeps from one frame to the next: the joints' marker indices and
// the storage of its iterations, so that fitting frame after frame allocates nothing but the
// result's pose. Made for one skeleton (its marker table); fit only that skeleton with it.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/hand/tracked_hand.h"

namespace handlab::hand {

struct FitWorkspace {
  explicit FitWorkspace(const Skeleton& tracked)
      : joint_marker(leap_joint_markers(tracked)), marker_count(tracked.markers.size()) {}
  // A copy is a fresh workspace for the same skeleton: the rest is scratch (and an LDLT that
  // never factorised holds an indeterminate status, which copying would read).
  FitWorkspace(const FitWorkspace& other)
      : joint_marker(other.joint_marker), marker_count(other.marker_count) {}
  FitWorkspace& operator=(const FitWorkspace& other) {
    joint_marker = other.joint_marker;  // the scratch is resized where it is used
    marker_count = other.marker_count;
    return *this;
  }

  std::array<int, 26> joint_marker;
  std::size_t marker_count;  // of the skeleton it was made for: a check, not a key
  std::vector<std::pair<int, Eigen::Vector3d>> targets;  // marker, its reported position
  std::vector<double> sqrt_weights;
  Eigen::VectorXd r, trial_r, g, step;
  Eigen::MatrixXd j, jtj, a;
  Eigen::Matrix<double, 3, Eigen::Dynamic> point_j;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  HandPose trial;
  BoneFrames frames, trial_frames;
};

}  // namespace handlab::hand
