// The index fingertip of the study hand pressed on a rigid plane: 1 N compresses the pad by
// 1-2 mm, as published fingertips do (the flesh's modulus and the distal capsule's thickness
// are calibrated to it), and the contact force grows with the compression as Hertz's
// F ~ d^1.5 says for a soft sphere on a plane, once more than one node of the pad touches.
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "core/hand/simulated_hand.h"
#include "core/sim/hand_simulator.h"

namespace handlab::sim {
namespace {

TEST(Fingertip, ForceFollowsHertzsTrend) {
  const hand::HandShape shape = hand::HandShape::with_length(0.214);
  const hand::Skeleton skeleton = hand::build_simulated_hand(shape);
  const hand::HandFlesh flesh = hand::build_flesh(skeleton, shape);
  // Palm down, tilted 20 degrees fingers-down, the other fingers lifted: the index pad is the
  // lowest point of the hand. No gravity: the plane's force is all the press.
  hand::HandPose pose = hand::HandPose::rest(skeleton);
  Eigen::Matrix3d palm_down;
  palm_down.col(0) = Eigen::Vector3d(0, 0, -1);
  palm_down.col(1) = Eigen::Vector3d(1, 0, 0);
  palm_down.col(2) = Eigen::Vector3d(0, -1, 0);
  pose.root_rotation =
      Eigen::AngleAxisd(-0.35, Eigen::Vector3d::UnitZ()).toRotationMatrix() * palm_down;
  pose.root_position = Eigen::Vector3d(0, 0.2, 0);
  for (std::size_t k = 0; k < skeleton.dofs.size(); ++k) {
    const hand::Dof& d = skeleton.dofs[k];
    if (d.name.rfind("index", 0) != 0 && d.name.find("flexion") != std::string::npos)
      pose.angles(Eigen::Index(k)) = d.lower;
  }
  SimParameters parameters;
  parameters.gravity.setZero();
  parameters.hand_floor_contact = true;
  parameters.floor_height = -1.0;  // out of reach while the hand settles
  Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
  root.linear() = pose.root_rotation;
  root.translation() = pose.root_position;
  RigidPose cube;
  cube.position = Eigen::Vector3d(1, 0.005, 1);
  const HandSimModel free_model = make_hand_sim_model(skeleton, flesh, parameters);
  HandSimState s = initial_state(free_model, skeleton, root, cube);
  {
    HandSimulator settle(free_model);
    const std::vector<RigidPose> targets = bone_targets(free_model, skeleton, pose);
    for (int i = 0; i < 30; ++i) settle.step(s, targets);
  }
  // The plane touches the lowest node, which is on the index's distal pad.
  std::size_t lowest = 0;
  for (std::size_t n = 0; n < s.node_position.size(); ++n)
    if (s.node_position[n].y() < s.node_position[lowest].y()) lowest = n;
  const int distal = skeleton.bone_index("index3");
  const hand::BoneFrames start = simulated_bone_frames(free_model, s);
  const Eigen::Vector3d local = start.rotation[std::size_t(distal)].transpose() *
                                (s.node_position[lowest] - start.origin[std::size_t(distal)]);
  ASSERT_GT(local.y(), 0.0) << "the lowest point should be on the distal phalanx";
  ASSERT_GT(local.z(), 0.0) << "on its pad";
  // The bone's point above the pad: how far it comes down is the pad's compression plus the
  // (small) penetration of the pad into the plane.
  const Eigen::Vector3d above(0, local.y(), 0);
  auto bone_height = [&](const hand::BoneFrames& f) {
    return (f.origin[std::size_t(distal)] + f.rotation[std::size_t(distal)] * above).y();
  };
  parameters.floor_height = s.node_position[lowest].y();
  const HandSimModel model = make_hand_sim_model(skeleton, flesh, parameters);
  HandSimulator sim(model);
  std::vector<double> force, compression;
  for (const double press : {0.5e-3, 1e-3, 1.5e-3, 2e-3}) {
    hand::HandPose pressed = pose;
    pressed.root_position.y() -= press;
    const std::vector<RigidPose> targets = bone_targets(model, skeleton, pressed);
    for (int i = 0; i < 60; ++i) sim.step(s, targets);
    double f = 0.0, depth_weighted = 0.0;
    for (const Eigen::Vector3d& x : s.node_position) {
      const double depth = parameters.floor_height - x.y();
      if (depth <= 0) continue;
      f += parameters.contact_stiffness * depth;
      depth_weighted += parameters.contact_stiffness * depth * depth;
    }
    ASSERT_GT(f, 0.0) << "the pad should press on the plane";
    const double surface = depth_weighted / f;
    force.push_back(f);
    compression.push_back(bone_height(start) - bone_height(simulated_bone_frames(model, s)) -
                          surface);
    std::cout << "pressed " << press * 1000 << " mm: " << f << " N, pad compressed "
              << compression.back() * 1000 << " mm\n";
  }
  for (std::size_t k = 1; k < force.size(); ++k) {
    EXPECT_GT(force[k], force[k - 1]);
    EXPECT_GT(compression[k], compression[k - 1]);
  }
  // The compression at 1 N, interpolated in log-log between the presses around it.
  ASSERT_LT(force.front(), 1.0);
  ASSERT_GT(force.back(), 1.0);
  std::size_t above_1n = 1;
  while (force[above_1n] < 1.0) ++above_1n;
  const double w =
      std::log(1.0 / force[above_1n - 1]) / std::log(force[above_1n] / force[above_1n - 1]);
  const double at_1n =
      std::exp((1 - w) * std::log(compression[above_1n - 1]) + w * std::log(compression[above_1n]));
  std::cout << "1 N compresses the pad " << at_1n * 1000 << " mm\n";
  EXPECT_GT(at_1n, 1e-3);
  EXPECT_LT(at_1n, 2e-3);
  // Hertz: log F / log d has slope 1.5 (a linear spring 1, a rigid stop infinity), while the
  // compression is small beside the pad's thickness (measured 1.61 from 0.43 to 1.54 mm;
  // pressed further, the bone's capsule comes near and the slope steepens).
  const double slope =
      std::log(force.back() / force.front()) / std::log(compression.back() / compression.front());
  std::cout << "log-log slope " << slope << " (Hertz 1.5)\n";
  EXPECT_GT(slope, 1.2);
  EXPECT_LT(slope, 1.9);
}

}  // namespace
}  // namespace handlab::sim
