// The constants that shape the simulated participant's own pinch postures (own_hand.h): chosen
// by looking at the own hand and its virtual hand holding each cube
// (docs/simulated-participants.md), never against a strategy comparison. Part of the model's
// hash (participant_model.h), each by name.
#pragma once

#include "studies/participant/pinch_ik.h"

namespace handlab::studies {

struct OwnHandPosture {
  // Pad pinch: palm down, rolled this far towards the thumb (rad, 60 degrees) so that thumb
  // and index oppose across the A-B line, as the simulator's pinch script holds both cubes.
  double pad_roll = 1.0471975511965976;
  double tip_roll = 0.3;   // rad: tip pinch, the palm nearly flat ...
  double tip_pitch = 0.5;  // rad: ... and the fingers pointing down
  double tip_tilt = 0.6;   // rad: the distal phalanges from the vertical, in a tip pinch
  // Middle, ring and little fingers, of their flexion range: curled out of the way in a closed
  // pinch, opening with it (the first postural synergy opens and closes all the digits
  // together: Santello, Flanders & Soechting 1998), extended at an aperture of `others_open_at`.
  double others_curl_closed = 0.7;
  double others_curl_open = 0.1;
  double others_open_at = 0.10;  // m between the pads
  // Where the pad is: this share of the distal bone's length along it, on its palmar surface.
  double pad_along = 0.55;
  double aim_depth = 0.012;    // m: the pad pinch's aiming points, this far behind the pads
  double tip_aim_along = 0.3;  // the tip pinch's aiming points: this share along the bone
  double tip_reach = 0.7;      // ... aimed at this share of the bone's length above the tips
  double aim_weight = 0.3;     // the aiming points' weight against the contact points' 1
  double widest_gap = 0.14;    // m: the posture table's widest aperture ...
  double gap_step = 0.005;     // m: ... down to 0 in these steps
  double keep_step = 1e-4;     // m: a posture kept when it opens this much wider than the last
  PinchIkOptions ik;           // the inverse kinematics that solves each posture
};

}  // namespace handlab::studies
