// A simulated participant's state in a trial, by what it is: what it learns in the trial from
// what it brought in (TrialLearning), the movements it has planned and is making
// (MovementPlan), and where it is in the task (PhaseState). Who it is and its memory of earlier
// trials are SimulatedPerson and ParticipantMemory; what it has seen is the participant's own.
#pragma once

#include <Eigen/Core>

#include "studies/participant/motor_primitives.h"
#include "studies/participant/own_hand.h"
#include "studies/participant/two_rate_adaptation.h"

namespace handlab::studies {

// Its practice and its adaptation within the trial, starting from its memory.
struct TrialLearning {
  double practised_movement = 1.0, practised_general = 1.0;
  TwoRateState contact;           // m: learnt correction of where it expects a pad to touch
  TwoRateState aim_x, aim_z;      // m: learnt shift of its aim across the floor
  double expected_contact = 0.0;  // m: own aperture where it expects a pad to meet the cube
  double gain_estimate = 1.0;     // seen aperture per own aperture, learnt while open
  int gain_samples = 0;
  double extra_squeeze = 0.0;  // m more loading after contact: the grip slips taught
  double grasp_lower = 0.0;    // m lower on the cube than its first choice: slips taught
  double caution = 0.0;        // share of practice's speed-up of the grasp given back
};

// The grasp it chose and the movements under way: the grip point's, the aperture's, the
// continuous visual correction on top, the tremor's phases.
struct MovementPlan {
  Pinch pinch = Pinch::kPad;
  double reaction_time = 0.0;
  MinimumJerkMove grip;
  double aperture_from = 0.04, aperture_to = 0.04, aperture_start = 0.0, aperture_duration = 0.0;
  Eigen::Vector3d servo = Eigen::Vector3d::Zero();  // continuous visual correction
  bool servo_on = false;
  int corrections_this_move = 0;
  Eigen::Vector3d tremor_phase = Eigen::Vector3d::Zero();
};

// Where it is in the task, and what it watches for there.
struct PhaseState {
  enum class Phase {
    kReact,
    kReach,
    kCheckReach,
    kDescend,
    kCheckDescent,
    kClose,
    kSlowClose,
    kConfirm,
    kLift,
    kCheckLift,
    kTransport,
    kCheckTransport,
    kLower,
    kRelease,
    kWaitRest,
    kWithdraw,
    kReopen,
    kFreeCube,  // a cube caught on the hand: open wide, then wipe it off on the floor
    kIdle
  };
  Phase phase = Phase::kReact;
  bool closing_touched = false;   // a pad seen on the cube since the closing began
  double off_floor_since = -1.0;  // the cube seen off the floor, not held, since then
  bool caught = false;            // the cube seen caught on the hand
  int wipes = 0;                  // of a caught cube on the floor, since it was seen caught
  bool slide_out = false;         // the cube came up with the withdrawing hand: slide out
  double touching_since = -1.0;
  double resting_since = -1.0;  // since when the cube has stayed near resting_at
  Eigen::Vector3d resting_at = Eigen::Vector3d::Zero();
};

}  // namespace handlab::studies
