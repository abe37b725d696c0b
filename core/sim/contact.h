// Contact: finding the candidates at the predicted state (contact_search.cpp), their energies
// (contact_energy.cpp: a normal penalty and a friction spring or force), and friction's
// decisions (friction.cpp: Coulomb's cone at a pass's result, the anchors the next step keeps).
// Flesh nodes and skin samples (points inside the boundary faces) touch the cube, flesh nodes
// (when the model says so) the floor; the cube's corners touch the floor.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/sim/box_distance.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/newton_terms.h"

namespace handlab::sim {

// A contact candidate, found at the predicted state. Its normal penalty acts whenever the
// point is inside the surface; its friction is decided at the predicted state: an anchor
// spring (sticking) or a kinetic force of mu f_n against the slip (sliding), the latter so that
// the anchor spring's stiffness does not hold back a slide's acceleration.
struct Contact {
  enum Kind { kNodeCube, kSampleCube, kNodeFloor, kCornerFloor } kind;
  int point;               // node, skin sample or corner
  Eigen::Vector3d normal;  // at the predicted state, in the surface's frame (cube or world)
  Eigen::Vector3d anchor;  // friction anchor, in the surface's frame
  int face = -1;           // flesh on the cube: the face it touches through (box_face's)
  bool touching = false;   // inside the surface at the predicted state: friction acts
  // The normal penalty's curvature is in Newton's matrix even where the point is outside:
  // from the start for points inside at the prediction, and from the next pass for points
  // that a pass without it carried inside (contacts_entered), so that a step lands where the
  // penalty balances the push instead of deep inside, and a resting cube does not chatter.
  bool curved = false;
  bool sliding = false;
  Eigen::Vector3d slip = Eigen::Vector3d::Zero();  // surface frame
  double friction_force = 0.0;                     // N
  int switches = 0;  // between sticking and sliding, in this step's passes
  // The normal in the world at the predicted state: the friction spring acts across it, held
  // through the step, so that its energy's gradient is exactly the force it exerts (a normal
  // turning with the cube would add a torque the spring's gradient leaves out, and the line
  // search would find the Newton step uphill).
  Eigen::Vector3d across = Eigen::Vector3d::Zero();
};

// Every point within a margin of a surface that covers what the bodies can move in a step.
// Those inside take friction: their anchor (from the step before, or where they entered)
// sticks, or, if the predicted state pulls it out of Coulomb's cone, they slide.
void find_contacts(const HandSimModel& model, const HandSimState& predicted,
                   std::vector<Contact>& contacts);

// The normal penalty wherever the point is inside (the exact distance, so that a point passing
// beside an edge feels nothing), friction as decided at the predicted state.
void add_contact_energies(const HandSimModel& model, const HandSimState& state,
                          const std::vector<Contact>& contacts, NewtonTerms& terms);

// Contacts whose curvature the solve left out but whose point ended inside the surface take it
// in the next pass (never taken out again, so that passes end). True if one did.
bool contacts_entered(const HandSimModel& model, const HandSimState& state,
                      std::vector<Contact>& contacts);

// Coulomb at a pass's result: a sliding contact whose point stopped short of the cone's edge
// sticks; a sticking one whose spring left the cone slides. True when some contact changed.
bool friction_changed(const HandSimModel& model, const HandSimState& state,
                      std::vector<Contact>& contacts);

// After the step: contacts that separated let go of their anchors; the others stick, or slide
// to the edge of the friction cone (|f_t| = mu f_n), into the state's anchor lists. Returns
// the deepest flesh point inside the cube (m).
double update_anchors(const HandSimModel& model, const std::vector<Contact>& contacts,
                      HandSimState& state);

// Shared by the three: a contact's point in its surface's frame (the cube's for flesh on the
// cube, else the world) and its signed distance from the surface (negative inside), with the
// cube's nearest surface point and normal for flesh on the cube.
struct ContactGap {
  Eigen::Vector3d x;
  double gap = 0.0;
  BoxProximity box;  // on the cube only
};
ContactGap contact_gap(const HandSimModel& model, const HandSimState& state, const Contact& c);
// The anchor of `point` in a list sorted by point (a state's), or null.
const ContactAnchor* find_anchor(const std::vector<ContactAnchor>& list, int point);
// A flesh point q (the cube's frame) against the cube, touching through `face` (-1: none yet):
// box_proximity, or box_proximity_through where the model keeps the face (contact_keeps_face).
BoxProximity flesh_on_cube(const HandSimModel& model, const Eigen::Vector3d& q, int face);
inline bool on_cube(const Contact& c) {
  return c.kind == Contact::kNodeCube || c.kind == Contact::kSampleCube;
}
// A flesh point's position in the world: a node's, or a skin sample's between its face's nodes.
Eigen::Vector3d flesh_point(const HandSimModel& model, const HandSimState& state, const Contact& c);
// Its Jacobian on the nodes' unknowns: the node's identity, or the sample's weights.
PointJacobian flesh_point_jacobian(const HandSimModel& model, const Contact& c);
// The normal penalty's stiffness at the surface (and the friction spring's), and its growth
// with depth: a flesh node's force is k d + k3 d^2 (soft where the skin first touches, so that
// the pad takes a light cube on several nodes; stiff deeper in, so that a heavy one does not
// sink). On the cube, the nodes and skin samples share them (cube_contact_share).
double contact_stiffness(const HandSimModel& model, const Contact& c);
double contact_stiffening(const HandSimModel& model, const Contact& c);
// The friction cone's radius about the anchor at a depth: mu f_n / k.
double friction_cone(const HandSimModel& model, const Contact& c, double depth);
// (I - n n') v: v's part across the normal n.
inline Eigen::Vector3d tangent_part(const Eigen::Vector3d& n, const Eigen::Vector3d& v) {
  return (Eigen::Matrix3d::Identity() - n * n.transpose()) * v;
}
// Corner k of the cube in the cube's frame (cube_corner's numbering).
Eigen::Vector3d corner_offset(const HandSimModel& model, int k);

}  // namespace handlab::sim
