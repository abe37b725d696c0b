// A simulated participant in one trial: a closed loop from what it sees (an Observation, one
// visual delay old) to the tracked frame of its own hand that it sends. It reaches, pre-shapes
// its grip, corrects what it sees go wrong, closes until it sees both pads on the cube, lifts,
// carries, places, lets go and withdraws (docs/simulated-participants.md). It knows nothing of
// the condition: its inputs are its own parameters, what it can see, and its own history.
#pragma once

#include <deque>
#include <vector>

#include "core/tracking/tracked_frame.h"
#include "studies/participant/motor_primitives.h"
#include "studies/participant/observation.h"
#include "studies/participant/own_hand.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/trial_experience.h"

namespace handlab::studies {

// What it knows of a trial before it starts, besides its own parameters.
struct TrialContext {
  int position = 0;    // the trial's place in its schedule (its random draws)
  int repetition = 1;  // trials done with this cube size (the one it sees), this one included
  double rate_hz = 120.0;
  SeenHandGeometry hand;  // how the simulated hand looks
};

class SimulatedParticipant {
 public:
  // `hand` (its own hand at its size) must outlive the participant.
  SimulatedParticipant(const SimulatedPerson& person, const OwnHand& hand, TrialContext context);

  // The frame it sends for the next tick, given what the display showed at the last one.
  tracking::TrackedFrame act(const Observation& shown);

  const TrialExperience& experience() const { return experience_; }
  const char* phase_name() const;
  // For traces: the pads' gaps to the cube in the newest observation it has taken in.
  double last_gap(bool thumb) const { return thumb ? last_seen_.thumb_gap : last_seen_.index_gap; }

 private:
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
  struct OwnState {
    double time;
    Eigen::Vector3d grip;
    double aperture;
  };
  struct Seen {  // what it makes of one observation
    bool hand = false;
    Eigen::Vector3d grip = Eigen::Vector3d::Zero();  // the virtual pads' midpoint
    double aperture = 0.0;                           // between the virtual pads' surfaces
    bool both_touching = false;                      // thumb and index pads on the cube
    double thumb_gap = 1.0, index_gap = 1.0;         // m from each pad's surface to the cube
    Eigen::Vector3d cube = Eigen::Vector3d::Zero();
  };

  const Observation* delayed() const;  // the newest observation at least one delay old
  Seen see(const Observation& o) const;
  OwnState own_at(double time) const;
  Eigen::Vector3d grasp_point(const Observation& o) const;
  double practice() const;
  double clearance(const Seen& s, const Observation& o) const;
  // Whether it has seen the cube stay put for a while (it watches on from each call).
  bool cube_at_rest(const Seen& s);
  static bool in_zone_b(const Seen& s, const Observation& o);
  void move_grip(const Eigen::Vector3d& target, double duration, bool noisy);
  void move_aperture(double target, double duration);
  void plan_reach(const Observation& o, const Seen& s);
  void start_regrasp();
  void update(const Observation* o);

  SimulatedPerson person_;
  const OwnHand& hand_;
  TrialContext context_;
  MotorRandom random_;
  double dt_;
  double time_ = 0.0;
  long frame_ = 0;
  std::deque<Observation> shown_;
  std::deque<OwnState> history_;
  Pinch pinch_ = Pinch::kPad;
  Phase phase_ = Phase::kReact;
  double phase_since_ = 0.0;
  double reaction_time_ = 0.0;
  MinimumJerkMove grip_;
  double aperture_from_ = 0.04, aperture_to_ = 0.04, aperture_start_ = 0.0,
         aperture_duration_ = 0.0;
  Eigen::Vector3d servo_ = Eigen::Vector3d::Zero();  // continuous visual correction
  bool servo_on_ = false;
  double gain_estimate_ = 1.0;  // seen aperture per own aperture, learnt while open
  int gain_samples_ = 0;
  double extra_squeeze_ = 0.0;
  double off_floor_since_ = -1.0;  // the cube seen off the floor, not held, since then
  int wipes_ = 0;                  // of a caught cube on the floor, since it was seen caught
  double touching_since_ = -1.0;
  double resting_since_ = -1.0;  // since when the cube has stayed near resting_at_
  Eigen::Vector3d resting_at_ = Eigen::Vector3d::Zero();
  int corrections_this_move_ = 0;
  Eigen::Vector3d tremor_phase_ = Eigen::Vector3d::Zero();
  TrialExperience experience_;
  Seen last_seen_;
};

}  // namespace handlab::studies
