// How a hand closes on a cube, as people close and a script does not: the pads' targets past
// the faces, the pinch's axis tilted from the faces' normal, the pads off the face's centre,
// one digit before the other, fast or slow, lifted briskly or gently, held short or long. Specified
// on the intermediate hand the soft hand follows, so that the grip is judged apart from any
// retargeting strategy
// (`handlab-cli sim grasp`, docs/simulator.md).
#pragma once

#include <string>
#include <vector>

namespace handlab::sim {

struct GraspClosing {
  double over_closure = 0.003;  // m: each pad's target this far past its face
  double tilt_yaw = 0.0;        // rad: the pinch's axis turned about the vertical
  double tilt_pitch = 0.0;      // rad: ... about the horizontal axis in the faces' plane
  double offset_along = 0.0;    // of the side: the pads moved along the faces, horizontally
  double lead_s = 0.0;          // s: the thumb closes this long before the index (< 0: after)
  double closing_speed = 0.0;   // m/s: each pad's mean speed as it closes; 0: the script's 0.5 s
  // m/s^2: the lift's peak acceleration (at its start: the lift follows a smoothstep, whose
  // peak is 6 height / duration^2); 0: the script's 10 cm in 1 s, 0.6 m/s^2.
  double lift_acceleration = 0.0;
  double hold_s = 5.0;        // s: lifted and held before the fingers open
  double jitter = 0.0;        // times a real recording's tracker jitter laid on the hand
  double jitter_phase = 0.0;  // where in the recording the jitter starts (of its length)
  // m: where the cube lies from where the hand aims, along the floor (x, z). Not a factor: a
  // cube never lies twice at the same spot, and the map's repeats (grasp_map.h) move it by a
  // tenth of a millimetre to find the closings whose outcome turns on such a detail.
  double cube_shift_x = 0.0, cube_shift_z = 0.0;
};

// A closing's factors by name ("over_closure", "tilt_yaw", ...), each with its value in the
// unit the command line takes (mm, degrees, fraction of the side, ms, cm/s, m/s^2, s).
struct ClosingFactor {
  std::string name, unit;
  double GraspClosing::*field;
  double scale;                // the unit in SI (0.001 for mm, pi/180 for degrees, ...)
  std::vector<double> levels;  // the grid's levels, in the command line's unit
  // The levels the pairs' grid crosses with each other factor's (about half its range).
  std::vector<double> pair_levels;
};
const std::vector<ClosingFactor>& closing_factors();
// The factor of that name; throws std::invalid_argument naming the factors for another name.
const ClosingFactor& closing_factor(const std::string& name);

// Sets factor `name` to `value` (the command line's unit); throws std::invalid_argument for an
// unknown name or a value outside the factor's range.
void set_closing_factor(GraspClosing& closing, const std::string& name, double value);

// Whether every factor of `closing` lies within about half of its range: between its pair
// levels (the pairs grid's), from the range's start where the range starts at 0 or above
// (over-closure 0-15 mm, speeds 2-16 cm/s, lifts 0.6-6 m/s^2, jitter 0-4 times), or at the
// scripted pinch's own value; a factor without pair levels (the hold) anywhere. Part of the
// map the grip must hold whole (docs/simulator.md).
bool within_half_of_ranges(const GraspClosing& closing);

// "over_closure 10 mm": a factor at a level (its unit's).
std::string describe_level(const ClosingFactor& factor, double level);

// "over_closure 10 mm, lead 100 ms" of the factors away from the default.
std::string describe(const GraspClosing& closing);

}  // namespace handlab::sim
