// The bodies' energies: the bone-flesh coupling springs, the penalty joints, the tracking
// springs towards the intermediate hand and their damping, gravity, and the kinetic terms of
// backward Euler.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/newton_matrix.h"
#include "core/sim/newton_terms.h"

namespace handlab::sim {

// The coupling springs (Eq. 2.11): each ties a point of the flesh (barycentric in a tet) to a
// point of a bone. `layout`, when given, holds their places in the panels.
void add_coupling(const HandSimModel& model, const HandSimState& state, NewtonTerms& terms,
                  const NewtonLayout* layout = nullptr);
// The penalty joints (Eq. 2.10): the child's joint centre as seen from both bodies, kept
// together by a stiff spring.
void add_joints(const HandSimModel& model, const HandSimState& state, NewtonTerms& terms,
                const NewtonLayout* layout = nullptr);
// Tracking: each bone's centre of mass towards its target's (one per bone, centres of mass)
// by a spring, and its rotation by a torsion spring on the rotation vector that separates them.
void add_tracking(const HandSimModel& model, const HandSimState& state,
                  const std::vector<RigidPose>& targets, NewtonTerms& terms);
// The tracking's damping (tracking_damping): each bone's move and turn since the step's `start`,
// by saturating dampers of tracking_damping times the tracking's stiffness and torsion.
void add_tracking_damping(const HandSimModel& model, const HandSimState& state,
                          const HandSimState& start, NewtonTerms& terms);
// Gravity on the bones, the cube and the flesh's nodes.
void add_gravity(const HandSimModel& model, const HandSimState& state, NewtonTerms& terms);

// The kinetic terms 1/2 |q - q_pred|^2_M from the step's `start` (its velocities carry the
// prediction on); `turned` holds each body's rotation vector since the start (bones, then the
// cube), whose inertia is taken in the world at the start. Unscaled: h^2 times the potential
// plus these is h^2 times the step's energy. The nodes' Hessian is their mass, which the
// matrix's product takes from the model; the bodies' enter as block terms.
void add_kinetic(const HandSimModel& model, const HandSimState& state,
                 const std::vector<Eigen::Vector3d>& turned, const HandSimState& start,
                 NewtonTerms& terms);

}  // namespace handlab::sim
