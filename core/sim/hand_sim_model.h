// The soft-hand simulator's immutable model (after Verschoor, Lobo & Otaduy 2018, as the
// ISMAR 2021 study used it): rigid bones joined by penalty joints, tetrahedral flesh with linear
// co-rotational FEM and a stiffening term, bone-flesh coupling springs, damped penalty contact with
// anchored Coulomb friction against a rigid cube and the floor, and elastic tracking springs
// towards the intermediate hand. The state it advances is in hand_sim_state.h.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/hand/flesh.h"
#include "core/hand/skeleton.h"
#include "core/mesh/tet_mesh.h"
#include "core/sim/rigid_body.h"
#include "core/sim/tet_element.h"

namespace handlab::sim {

// Physical parameters, SI units; docs/simulator.md says where each value comes from.
struct SimParameters {
  double time_step = 1.0 / 120.0;  // s
  Eigen::Vector3d gravity = Eigen::Vector3d(0, -9.81, 0);
  // Flesh: soft tissue of the fingertip pad, ν near incompressible.
  Material flesh = {50e3, 0.45};
  double flesh_density = 1050.0;  // kg/m^3
  // Stiffening: beyond this corotated strain norm the tissue stiffens by this factor's modulus
  // (an energy (factor E V / 2)(|e| - threshold)^2 on top of the linear one).
  double stiffening_strain = 0.25;
  double stiffening_factor = 20.0;
  // Newton's matrix takes in the stiffening's curvature, blended in smoothly, from this
  // fraction of the threshold below it (the energy and forces are unchanged). Without it the
  // matrix jumps by 20 E where a tet crosses the threshold, and one Newton iteration a step
  // overshoots across it, back and forth: held still, flesh nodes buzz at 30-60 Hz.
  double stiffening_blend = 0.2;
  // Where the blend is not enough: a pass in which no flesh touches anything iterates again
  // while its step stopped short, the energy falling by more than 1 + short_step_excess times its
  // quadratic model's decrease (step_solver.cpp; docs/simulator.md, "The short step's
  // iterations": at 0.25 every held pose measured comes to rest). 0: never.
  double short_step_excess = 0.25;
  double bone_density = 1500.0;        // kg/m^3 (bone with marrow)
  double coupling_stiffness = 1e8;     // N/m per m^2 of bone surface a coupling point stands for
  double joint_stiffness = 2e4;        // N/m, the penalty joints
  double tracking_stiffness = 2000.0;  // N/m per bone, towards the intermediate hand
  double tracking_torsion = 2.0;       // N m/rad per bone
  // The finger bones' tracking saturates (saturating_spring.h): a virtual coupling's bound, so
  // that a finger whose target lies deep inside the cube presses as a hand would, not with a
  // force that grows with the depth. 0: linear springs. The palm, which the arm carries,
  // tracks linearly.
  double tracking_force_limit = 0.0;   // N per finger bone
  double tracking_torque_limit = 0.0;  // N m per finger bone
  // Each bone's motion damped against the world, so that a target that jumps a little, as a
  // tracker's jitter does, is followed as through a first-order lag of tracking_damping (the
  // damper is tracking_damping times the tracking's stiffness and torsion), while the hand's
  // own motion is held back little: the damper's force saturates past tracking_damping_speed
  // (saturating_damper.h; a turn past that over 2 cm), so that a fast move adds little more
  // than tracking_damping x tracking_damping_speed to a bone's lag behind its target. 0: no
  // damping; a speed of 0: a linear damper. The values were chosen on the grasp map
  // (docs/simulator.md, "The tracking's damping").
  double tracking_damping = 0.025;       // s
  double tracking_damping_speed = 0.07;  // m/s
  // Contact: normal penalty per contact point, the friction anchor spring, Coulomb's
  // coefficients (below).
  double contact_stiffness = 5e3;     // N/m, a flesh node against the cube or floor, at first
  double contact_stiffening = 2.5e7;  // N/m^2: its force k d + k3 d^2 at a depth d
  // A cube corner against the floor: its force k d + k3 d^2. The stiffening keeps a cube that a
  // hand presses onto the floor from storing the press and throwing it when let go (143 N on
  // the 6 cm cube: 59 um deep, where the linear corner's 3.6 mm would lift it 24 cm); the value
  // chosen on the grasp maps (docs/simulator.md, "The cube's substeps on a stiff floor").
  double cube_floor_stiffness = 1e4;    // N/m
  double cube_floor_stiffening = 1e10;  // N/m^2
  // Contact points against the cube inside each boundary face of the flesh, besides its nodes:
  // 0 or 1 (the centroid). With the nodes alone the cube's edges and corners sank into the
  // skin between them (1.7 mm in the scripted light pinch's hold).
  // The nodes and samples share contact_stiffness (HandSimModel::cube_contact_share).
  int skin_samples = 1;
  // A flesh point inside the cube is pushed out through the face it touched when its contact
  // began (kept with its friction anchor; a new contact's, the face its point lies farthest
  // outside of at the step's prediction), not through the face now nearest: near an edge, a
  // pad pressed into a side face otherwise pushes the cube through the bottom or the face
  // beside it. A point that leaves the cube sideways, below its kept face, loses its penalty
  // at once (the energy steps down there). Off: the nearest face.
  bool contact_keeps_face = false;
  // Damping of flesh on the cube along the contact's normal, in proportion to the contact's
  // force (Hunt & Crossley 1975: f = k d + k3 d^2 + contact_damping (k d + k3 d^2) v, v the
  // depth's rate): a point's depth and force at the step's start set the damper for the step.
  // Chosen on the grasp maps; no source for the skin's value on a penalty contact (an
  // assumption: at 0.05 m/s a point's force grows by a quarter). 0: off.
  double contact_damping = 5.0;  // s/m
  // A step in which flesh first touches the cube taken again in substeps of about this length
  // (the time step divided by the nearest whole number), and the steps within
  // contact_substep_window after it too (core/sim/contact_substeps). 0: off.
  double contact_time_step = 1.0 / 1920;  // s
  double contact_substep_window = 0.1;    // s
  // Those substeps take the cube alone against the flesh's path, the hand's step left as it is
  // (core/sim/cube_substeps), not the whole hand again.
  bool contact_substeps_cube = true;
  // And in every step, past the window too, in which flesh touches a cube that moves on the
  // floor (not at rest on four corners: FreeCubeStepper's rule), so that no moving cube's floor
  // contact is solved at the hand's step, whose one Newton iteration a stiffened floor defeats.
  // Off: on the grasp maps it holds no more, and it loses the scripted light pinch without a
  // squeeze (docs/simulator.md, "The cube's substeps on a stiff floor").
  bool cube_substeps_on_floor = false;
  // Coulomb's coefficients: the cube on the floor (and flesh on the floor), and the skin on the
  // cube, two pairs of materials (skin on wood or plastic: 0.5-1; fingertip skin 0.6 on
  // aluminium and 0.9 on rubber over 1-20 N, falling by 46 % from 1 to 20 N: Seo & Armstrong
  // 2009, Ergonomics 52(5):609).
  double friction = 0.8;
  double skin_friction = 0.8;
  bool hand_floor_contact = false;  // the study: off
  Eigen::Vector3d floor_normal = Eigen::Vector3d::UnitY();
  double floor_height = 0.0;    // the floor: floor_normal . x = floor_height
  double cube_size = 0.01;      // m (the study: 0.06 gross, 0.01 fine)
  double cube_density = 500.0;  // kg/m^3 (wood)
};

// A point of the skin inside a boundary face of the flesh, a contact point against the cube.
struct SkinSample {
  std::array<int, 3> nodes{};
  Eigen::Vector3d weights;  // barycentric, summing to 1
};

// A bone as a rigid body: its frame is the skeleton bone's frame moved to the centre of mass.
struct SimBone {
  int parent = -1;
  RigidInertia inertia;            // about the centre of mass, bone-frame axes
  Eigen::Vector3d centre_in_bone;  // the centre of mass in the skeleton bone's frame
};

// The penalty joint between a bone and its parent (Eq. 2.10): the child's joint centre,
// seen from both bodies' centres of mass, kept together by a stiff spring.
struct SimJoint {
  int parent = 0, child = 0;
  Eigen::Vector3d in_parent, in_child;  // body frames
};

// A bone-flesh coupling spring (Eq. 2.11): a point of the flesh (barycentric in a tet) tied to
// a point of a bone.
struct SimCoupling {
  int bone = 0;
  std::array<int, 4> nodes{};
  Eigen::Vector4d weights;
  Eigen::Vector3d in_bone;  // body frame
  double stiffness = 0.0;   // N/m
};

struct HandSimModel {
  SimParameters parameters;
  // Flesh
  std::vector<Eigen::Vector3d> rest;  // nodes at rest, in the hand's root frame
  std::vector<TetElement> tets;
  std::vector<double> node_mass;
  std::vector<int> surface_nodes;        // nodes on the flesh's boundary: the contact points
  std::vector<SkinSample> skin_samples;  // and points between them, against the cube
  // The part of contact_stiffness (and contact_stiffening) each flesh point on the cube takes:
  // nodes / (nodes + samples), so that the skin is as stiff per area as with nodes alone.
  double cube_contact_share = 1.0;
  // The nodes move where their velocities carry them, placed by the caller: the step's
  // unknowns are the cube's alone (the flesh points of the cube's substeps, cube_substeps.h;
  // a model with bones cannot have them).
  bool kinematic_nodes = false;
  // Bones
  std::vector<SimBone> bones;
  std::vector<SimJoint> joints;
  std::vector<SimCoupling> coupling;
  // The skin each bone carries: the surface nodes nearest it at rest (its capsules'), at rest
  // in its body frame (about its centre of mass): what a posture keeps clear of the cube.
  std::vector<std::vector<Eigen::Vector3d>> bone_skin;
  std::vector<int> node_bone;  // each node's bone of bone_skin (-1: not a surface node)
  // The cube
  RigidInertia cube;
  Eigen::Vector3d cube_half = Eigen::Vector3d::Zero();

  int node_count() const { return int(rest.size()); }
  int bone_count() const { return int(bones.size()); }
  // Unknowns: 3 per node, 6 per bone, 6 for the cube.
  int dof_count() const { return 3 * node_count() + 6 * bone_count() + 6; }
};

// The study's hand: the skeleton and its flesh (hand/flesh.h), in the root frame at rest.
HandSimModel make_hand_sim_model(const hand::Skeleton& skeleton, const hand::HandFlesh& flesh,
                                 const SimParameters& parameters = {});
// Only the cube and the floor (no hand), for rigid-body and contact tests.
HandSimModel make_cube_sim_model(const SimParameters& parameters = {});
// A free body of flesh (no bones), the cube and the floor, for contact tests.
HandSimModel make_soft_body_sim_model(const mesh::TetMesh& mesh,
                                      const SimParameters& parameters = {});

// The faces on a tet mesh's boundary (that only one tet has), their nodes in ascending order,
// and the nodes on them.
std::vector<std::array<int, 3>> boundary_faces(const std::vector<std::array<int, 4>>& tets);
std::vector<int> boundary_nodes(const std::vector<std::array<int, 4>>& tets, int node_count);

}  // namespace handlab::sim
