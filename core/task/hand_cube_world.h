// The physics a trial runs on, behind one interface: a hand driven towards the
// intermediate hand, and the cube it manipulates. The trial driver, the task and the frame
// log see only this, so the soft-hand simulator (docs/simulator.md) replaces the grasp
// proxy without touching them.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "core/hand/skeleton.h"

namespace handlab::task {

struct CubeState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centre (m)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
};

class HandCubeWorld {
 public:
  virtual ~HandCubeWorld() = default;
  // Advances by dt (s) towards the intermediate hand; nullptr while no hand is tracked.
  virtual void step(const hand::HandPose* target, double dt) = 0;
  virtual const CubeState& cube() const = 0;
  virtual bool thumb_contact() const = 0;
  virtual bool index_contact() const = 0;
  // World poses of the simulated hand's bones (empty before the first hand).
  virtual const std::vector<Eigen::Isometry3d>& bones() const = 0;
};

}  // namespace handlab::task
