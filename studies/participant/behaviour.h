// The fixed constants of a simulated participant's behaviour, the same for every person (the
// per-person parameters are MotorParameters): heights, margins, the looks it takes. Each with
// its reason or source in docs/simulated-participants.md; part of the model's hash, each by
// its name (participant_model.cpp; the struct holds doubles only, so none is left out).
#pragma once

namespace handlab::studies {

struct Behaviour {
  double approach_height = 0.04;  // m above the grasp point before coming down
  double lift_height = 0.08;      // m
  double withdraw_height = 0.10;  // m
  // m: it sets the cube down until it sees it on the floor, aiming this far past (the cube
  // stops there and the pads slide on it), so that the floor holds it as the fingers open.
  double place_depth = 0.001;
  double release_opening = 0.03;  // m the aperture opens to let go
  double slow_closing = 0.02;     // m/s when the planned closing did not reach the cube
  double servo_gain = 3.0;        // 1/s, continuous visual correction
  double max_corrections = 3;     // corrective submovements per aimed movement
  // The cube looks at rest when it stays within rest_travel of where it was for rest_look: a
  // person sees whether it still slides or tumbles, not a fingertip's tremor nudging it.
  double rest_travel = 0.002;            // m
  double rest_look = 0.2;                // s
  double pre_contact_margin = 0.015;     // m each side of the cube before the closing
  double closing_past_contact = 0.0015;  // m the closing aims past the seen size
  double grip_loading = 0.0015;          // m it closes on after seeing contact (loading phase)
  double tip_pinch_below = 0.02;         // m: a cube this small is picked with the tips
  double pad_on_face = 0.007;            // m: a pad's bone this close (surface) is on the cube
  // A cube seen this high for this long without both pads on it is caught on the hand (a
  // dropped cube falls from the lift's height in a seventh of a second).
  double caught_height = 0.02;  // m
  double caught_look = 0.2;     // s
  double wipe_depth = 0.01;     // m under the floor it takes a caught cube to wipe it off
  // Durations of the moves that are not aimed (no Fitts target), before practice.
  double reopen_time = 0.3;       // s: opening the hand again, to let go or free a cube
  double reopen_rise_time = 0.4;  // s: rising over the cube to grasp again
  // Its estimate of how the seen aperture follows its own: taken while the hand is open wider
  // than gain_min_aperture, smoothed over frames with this weight on the newest.
  double gain_min_aperture = 0.03;  // m
  double gain_smoothing = 0.05;
  double min_gain = 0.3;                   // the estimate it trusts at least
  double min_tolerance = 0.002;            // m: the finest correction tolerance
  double reach_tolerance_share = 0.25;     // of the clearance at the end of the reach
  double centring_tolerance_share = 0.25;  // of the cube's side before closing
  double min_clearance = 0.004;            // m: the clearance it counts on at least
  double loss_distance = 0.015;            // m past the cube's half side: the cube left the pads
  double placement_tolerance = 0.005;      // m: the least it accepts over B
  double placement_margin = 0.01;          // m inside B's edge
  double at_rest_over_floor = 0.01;  // m: a cube this high after letting go is still on the hand
  double home_height = 0.15, home_back = 0.12;  // m: where the hand rests before a trial
  double rest_aperture = 0.04;                  // m: the loosely open fingers at rest
  // m: the hand length at which the peak aperture's margin is the drawn intercept (the
  // study sample's mean); a person's margin scales with its hand.
  double reference_hand_length = 0.188;
};

}  // namespace handlab::studies
