// The flesh's normal contact forces on the cube at a state, per face of the cube: what a grip
// presses with (the pinch's two faces), read from the contacts the state holds.
#pragma once

#include <array>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"

namespace handlab::sim {

// N, on the faces -x, +x, -y, +y, -z, +z of the cube's own frame (index 2 axis + side): the
// normal penalty of every flesh node and skin sample in contact (those the state's anchors
// hold), each on the face nearest to it.
std::array<double, 6> flesh_forces_on_cube_faces(const HandSimModel& model,
                                                 const HandSimState& state);

}  // namespace handlab::sim
