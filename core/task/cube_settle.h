// A cube set moving on the floor with nothing else touching it: when it comes to rest, how far
// it goes, how high its centre rises and the most energy it ever has, beside what its starting
// energy allows. Coulomb's friction must take all of that energy: a slide no longer than
// E0 / (mu m g), and no rise of the centre that E0 cannot pay for. A check of the cube's floor
// contact and friction, on which a light cube that fingers flick depends.
// A client of the simulator (in its namespace), kept out of its stages in core/sim.
#pragma once

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/sim_options.h"

namespace handlab::sim {

struct CubeKick {
  double speed = 0.0;  // m/s, along (1, 0, 0.3): mostly along x, a little across
  // rad/s, about (0.5, 0, 1): a backspin over its edges (its bottom slips faster than its
  // centre moves), with some roll. The simulator bounds a cube's spin (30 rad/s at 1/120 s):
  // a faster kick loses the excess in its first step, which E0 still counts.
  double spin = 0.0;
};

struct CubeSettleReport {
  double rest_time = -1.0;      // s after the kick when it came to rest (-1: not within the run)
  double travelled = 0.0;       // m, its centre's distance along the floor at the end
  double slide_bound = 0.0;     // m, E0 / (mu m g): the furthest its starting energy can slide it
  double highest_rise = 0.0;    // m, its centre above where it rested before the kick
  double start_energy = 0.0;    // J, kinetic (both parts) at the kick
  double highest_energy = 0.0;  // J, kinetic plus gravity's above the rest height, after it
};

// The cube's kinetic energy, translational and rotational, plus gravity's above the floor (J).
double cube_energy(const HandSimModel& model, const HandSimState& state);

// The cube alone, resting flat on the floor (settled for 0.25 s), kicked, then stepped for
// `duration` seconds. At rest from the first moment after which it stays within 0.1 mm and
// 0.01 rad of where it ends (for at least the run's last 0.1 s; else it has not come to rest).
CubeSettleReport settle_cube(const SimParameters& parameters, const CubeKick& kick,
                             const SimOptions& options = {}, double duration = 5.0);
// The same for the cube of `state` in any model without bones (a free body of flesh beside
// it, say), flat on the floor.
CubeSettleReport settle_cube(const HandSimModel& model, HandSimState state, const CubeKick& kick,
                             const SimOptions& options = {}, double duration = 5.0);

}  // namespace handlab::sim
