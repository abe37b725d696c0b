// A kinematic hand-cube world: the hand's bones sit exactly on the intermediate hand, the
// cube is a rigid body under gravity on the floor, and a pinch attaches it. The cube is
// grasped when the thumb and index fingertips (spheres of the distal bones' radii) both
// touch it from opposite sides, follows their midpoint while both stay within a release
// margin, and falls when either leaves. This is the attachment model common in VR toolkits,
// and the trials' default; SoftHandWorld runs them on the soft-hand simulator instead
// (docs/study.md says what differs).
#pragma once

#include "core/hand/skeleton.h"
#include "core/task/hand_cube_world.h"

namespace handlab::task {

struct GraspProxySettings {
  double cube_size = 0.06;        // m
  double touch_margin = 0.001;    // m beyond the fingertip sphere that still counts as touching
  double release_margin = 0.004;  // m: a grasped cube is let go beyond this
  double gravity = 9.81;          // m/s^2, along -y
};

class GraspProxyWorld : public HandCubeWorld {
 public:
  // `skeleton` is the simulated hand's and must outlive the world.
  GraspProxyWorld(const hand::Skeleton& skeleton, GraspProxySettings settings,
                  const Eigen::Vector3d& cube_start);

  void step(const hand::HandPose* target, double dt) override;
  const CubeState& cube() const override { return cube_; }
  bool thumb_contact() const override { return thumb_contact_; }
  bool index_contact() const override { return index_contact_; }
  const std::vector<Eigen::Isometry3d>& bones() const override { return bones_; }
  bool grasped() const { return grasped_; }

 private:
  double distance_to_cube(const Eigen::Vector3d& point) const;

  const hand::Skeleton& skeleton_;
  GraspProxySettings settings_;
  int thumb_tip_, index_tip_;
  double thumb_radius_, index_radius_;
  CubeState cube_;
  bool grasped_ = false;
  Eigen::Vector3d grip_offset_ = Eigen::Vector3d::Zero();  // cube centre - tip midpoint
  bool thumb_contact_ = false, index_contact_ = false;
  hand::BoneFrames frames_;
  std::vector<Eigen::Isometry3d> bones_;
};

}  // namespace handlab::task
