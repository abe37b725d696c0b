// How a Newton increment dq of the unknowns moves a state: node positions and the bodies'
// translations by length dq, each body's rotation turned by the rotation vector length dq (in
// the world, on the left), and `turned` (each body's rotation vector since the step began:
// bones, then the cube) by the same. The step's energies are functions of the unknowns in this
// parametrisation; their gradients and Hessians are with respect to it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"

namespace handlab::sim {

void apply_increment(const HandSimModel& model, HandSimState& state,
                     std::vector<Eigen::Vector3d>& turned, const Eigen::VectorXd& dq,
                     double length);

}  // namespace handlab::sim
