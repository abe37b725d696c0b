// The soft-hand simulator (core/sim, docs/simulator.md) behind the trials' world interface:
// the simulated hand's bones are pulled towards the intermediate hand, its flesh touches the
// cube, and the cube moves only by the contact and friction forces, gravity and the floor.
// Thumb or index "contact" is a flesh node of that finger (any of its three phalanges: a large
// cube is often held between the thumb's pad and the side of the index's middle phalanx) on
// the cube.
#pragma once

#include <memory>
#include <vector>

#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/hand_simulator.h"
#include "core/sim/step_totals.h"
#include "core/task/hand_cube_world.h"

namespace handlab::task {

class SoftHandWorld : public HandCubeWorld {
 public:
  // `model` (with the condition's cube) and `skeleton` (the simulated hand's, whose flesh the
  // model holds) must outlive the world. The hand appears, at rest in the first target's
  // root frame, with the first target.
  SoftHandWorld(const sim::HandSimModel& model, const hand::Skeleton& skeleton,
                const Eigen::Vector3d& cube_start, sim::SimOptions options = {});

  // Advances by dt in the simulator's fixed steps (time left over is carried to the next
  // call). Without a target the hand keeps pulling towards the last one.
  void step(const hand::HandPose* target, double dt) override;
  const CubeState& cube() const override { return cube_; }
  bool thumb_contact() const override { return thumb_contact_; }
  bool index_contact() const override { return index_contact_; }
  const std::vector<Eigen::Isometry3d>& bones() const override { return bones_; }

  // The simulator's state (null before the first target).
  const sim::HandSimState* state() const { return state_.get(); }
  // What its steps have cost since the world was made.
  const sim::StepTotals& totals() const { return totals_; }

 private:
  void observe();

  const sim::HandSimModel& model_;
  const hand::Skeleton& skeleton_;
  sim::HandSimulator simulator_;
  sim::RigidPose cube_start_;
  std::unique_ptr<sim::HandSimState> state_;
  std::vector<sim::RigidPose> targets_;
  enum Finger { kOther, kThumb, kIndex };
  std::vector<int> node_bone_;  // the bone each flesh node lies nearest to at rest
  std::vector<Finger> finger_;  // of each bone
  double pending_ = 0.0;        // s not yet simulated
  CubeState cube_;
  bool thumb_contact_ = false, index_contact_ = false;
  std::vector<Eigen::Isometry3d> bones_;
  sim::StepTotals totals_;
};

}  // namespace handlab::task
