// Damping of flesh on the cube (SimParameters::contact_damping): along each contact's normal a
// force c v, v the depth's rate since the step's start and c the contact_damping times the
// penalty's force there (Hunt & Crossley 1975), as a spring of c / h from where the point lay
// in the cube then (backward Euler's incremental potential of a dashpot).
#pragma once

#include <vector>

#include "core/sim/contact.h"

namespace handlab::sim {

// A contact's damper: where its point lay at the step's start (the cube's frame then) and the
// penalty's force there (0: outside, no damper).
struct ContactDamper {
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();
  double force = 0.0;
};

// One damper a contact (none but on the cube), from `start`, the step's start state.
void set_contact_dampers(const HandSimModel& model, const HandSimState& start,
                         const std::vector<Contact>& contacts, std::vector<ContactDamper>& dampers);

// The dampers of the contacts touching the cube at `state`.
void add_contact_damping(const HandSimModel& model, const HandSimState& state,
                         const std::vector<Contact>& contacts,
                         const std::vector<ContactDamper>& dampers, NewtonTerms& terms);

}  // namespace handlab::sim
