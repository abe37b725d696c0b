// The cube as the hand's simulator steps it where no flesh touches it: beside one tet of flesh a
// metre away (hand-floor contact is off, as in the study: the tet falls through the floor and
// never comes near), so that the model is a hand's and a moving cube goes in the free cube's
// substeps (core/sim/free_cube.h), a resting one in the hand's step.
#pragma once

#include <Eigen/Geometry>

#include "core/mesh/tet_mesh.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"

namespace handlab::sim {

inline HandSimModel lone_cube_model(const SimParameters& p) {
  const mesh::TetMesh tet{{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.03, 0, 0.02),
                           Eigen::Vector3d(0, 0.03, 0.02), Eigen::Vector3d(0, 0, 0.05)},
                          {{0, 1, 2, 3}}};
  return make_soft_body_sim_model(tet, p);
}

inline HandSimState lone_cube_state(const HandSimModel& model, const RigidPose& cube) {
  const Eigen::Isometry3d away(Eigen::Translation3d(1.0, 0.5, 0.0));
  return initial_state(model, {}, away, cube);
}

}  // namespace handlab::sim
