// The simulated participant's own hand: the tracked skeleton of its size (what a Leap
// reports of it) in a pinch posture indexed by the thumb-index aperture, placed by the
// contact points' midpoint (the grip point). Two pinches, as people choose them by the
// object's size: the pad pinch (the distal pads facing each other) and the tip pinch (the
// fingertips meeting from above, for small objects). Each posture family comes from inverse
// kinematics of the contact points, computed once per hand.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/tracking/tracked_frame.h"
#include "studies/participant/own_hand_posture.h"

namespace handlab::studies {

enum class Pinch { kPad, kTip };

class OwnHand {
 public:
  // The postures of a hand of this length (m), shaped by the model's own_hand_posture.h.
  explicit OwnHand(double hand_length);

  // The pose of a pinch with the contact points `aperture` apart (m, surface to surface,
  // clamped to what the hand reaches) and their midpoint at `grip`.
  hand::HandPose pose(Pinch pinch, const Eigen::Vector3d& grip, double aperture) const;
  // The open palm (fingers extended, palm down) with its palm centre at `palm`.
  hand::HandPose open_palm(const Eigen::Vector3d& palm) const;
  // What the tracker reports of a pose (right hand), with each joint displaced by `jitter`
  // (m, one vector per digit and joint, may be empty).
  tracking::TrackedFrame frame(const hand::HandPose& pose, double time, long id,
                               const std::vector<Eigen::Vector3d>& jitter) const;

  double min_aperture(Pinch pinch) const { return table(pinch).front().aperture; }
  double max_aperture(Pinch pinch) const { return table(pinch).back().aperture; }
  const hand::Skeleton& skeleton() const { return skeleton_; }

 private:
  struct Posture {
    double aperture;  // m between the pads
    Eigen::VectorXd angles;
    Eigen::Vector3d grip_from_root;  // the pads' midpoint relative to the root position
  };
  struct Table {
    Eigen::Matrix3d rotation;
    std::vector<Posture> postures;  // by increasing aperture
  };
  const std::vector<Posture>& table(Pinch pinch) const {
    return pinch == Pinch::kPad ? pad_.postures : tip_.postures;
  }
  Table build(bool tip, const Eigen::Matrix3d& rotation) const;

  hand::Skeleton skeleton_;
  Table pad_, tip_;
};

}  // namespace handlab::studies
