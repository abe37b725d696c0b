// What a simulation step advances: flesh nodes, bones and the cube, and the contacts'
// friction anchors (the model is in hand_sim_model.h).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/rigid_body.h"

namespace handlab::sim {

// A contact point held by a friction anchor: where on the other surface the point sticks
// (Eq. 2.12-2.13). The anchor slides when the friction force would leave Coulomb's cone.
struct ContactAnchor {
  int point = 0;           // a flesh node, a skin sample, or a cube corner (0..7)
  Eigen::Vector3d anchor;  // on the cube (cube frame) or on the floor (world)
  int face = -1;           // flesh on the cube: the face it touches through (box_face's)
};

struct HandSimState {
  double time = 0.0;
  std::vector<Eigen::Vector3d> node_position, node_velocity;
  std::vector<Eigen::Quaterniond> tet_rotation;  // warm starts of the rotation extraction
  std::vector<RigidPose> bone_pose;              // centres of mass
  std::vector<RigidVelocity> bone_velocity;
  RigidPose cube_pose;
  RigidVelocity cube_velocity;
  std::vector<ContactAnchor> node_cube, sample_cube, node_floor, corner_floor;
};

// The hand in its rest pose (the flesh undeformed), its root frame (the wrist) at `root`; the
// cube at `cube`; everything at rest.
HandSimState initial_state(const HandSimModel& model, const hand::Skeleton& skeleton,
                           const Eigen::Isometry3d& root, const RigidPose& cube);

// Corner k (0..7) of the cube at `pose`: its x, y and z signs are bits 0, 1 and 2 of k (set:
// +, clear: -), the numbering of ContactAnchor::point for corners.
Eigen::Vector3d cube_corner(const HandSimModel& model, const RigidPose& pose, int k);

// Skin sample i's position at `state` (between its face's nodes).
Eigen::Vector3d skin_sample_position(const HandSimModel& model, const HandSimState& state, int i);

// The bodies' targets (centres of mass) for the bone frames of a pose of the skeleton.
std::vector<RigidPose> bone_targets(const HandSimModel& model, const hand::Skeleton& skeleton,
                                    const hand::HandPose& pose);

// The skeleton bone frames (origin, rotation) of the simulated bones.
hand::BoneFrames simulated_bone_frames(const HandSimModel& model, const HandSimState& state);

}  // namespace handlab::sim
