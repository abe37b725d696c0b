// Flesh turned inside out: tets whose deformation gradient's determinant is not positive. The
// co-rotational flesh (flesh_energy.h) does not resist inversion, so a region crushed past it
// (the thumb's base bent into opposition with the stiffening off) stays inverted, its
// rotations flipping from step to step: a count of such tets tells a sound flesh from a
// tangled one.
#pragma once

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"

namespace handlab::sim {

// The flesh's tets at `state` with det F <= 0.
int inverted_tet_count(const HandSimModel& model, const HandSimState& state);

}  // namespace handlab::sim
