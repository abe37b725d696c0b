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
#include "studies/participant/participant_memory.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/participant_state.h"
#include "studies/participant/seen_trial.h"
#include "studies/participant/trial_experience.h"

namespace handlab::studies {

class SimulatedParticipant {
 public:
  // Who it is, its own hand at its size (must outlive the participant), what it knows of the
  // trial and what it carries from its earlier trials.
  SimulatedParticipant(const SimulatedPerson& person, const OwnHand& hand, const SeenTrial& trial,
                       ParticipantMemory memory);

  // The frame it sends for the next tick, given what the display showed at the last one.
  tracking::TrackedFrame act(const Observation& shown);

  const TrialExperience& experience() const { return experience_; }
  // What it carries out of the trial (so far): its memory with this trial's experience.
  ParticipantMemory memory_after() const;
  const char* phase_name() const;
  // For traces and kinematics: its own hand's aperture between the pads (m) and grip point,
  // as sent with the last frame.
  double own_aperture() const { return history_.empty() ? 0.0 : history_.back().aperture; }
  Eigen::Vector3d own_grip() const {
    return history_.empty() ? Eigen::Vector3d::Zero() : history_.back().grip;
  }
  // For traces: the pads' gaps to the cube in the newest observation it has taken in.
  double last_gap(bool thumb) const { return thumb ? last_seen_.thumb_gap : last_seen_.index_gap; }

 private:
  using Phase = PhaseState::Phase;
  struct OwnState {
    double time;
    Eigen::Vector3d grip;
    double aperture;
  };
  struct Seen {  // what it makes of one observation
    bool hand = false;
    Eigen::Vector3d grip = Eigen::Vector3d::Zero();  // the virtual pads' midpoint
    double aperture = 0.0;                           // between the virtual pads' surfaces
    bool thumb_on = false, index_on = false;         // each pad seen on the cube
    bool both_touching = false;                      // thumb and index pads on the cube
    double thumb_gap = 1.0, index_gap = 1.0;         // m from each pad's surface to the cube
    Eigen::Vector3d cube = Eigen::Vector3d::Zero();
  };

  Activity activity() const;           // what the phase it is in is part of
  const Observation* delayed() const;  // the newest observation at least one delay old
  Seen see(const Observation& o) const;
  OwnState own_at(double time) const;
  Eigen::Vector3d grasp_point(const Observation& o) const;
  double clearance(const Seen& s, const Observation& o) const;
  // Whether it has seen the cube stay put for a while (it watches on from each call).
  bool cube_at_rest(const Seen& s);
  static bool in_zone_b(const Seen& s, const Observation& o);
  double aperture_now() const;
  // Its first sight of the scene: the pinch for the cube, practice, what it expects.
  void start(const Observation& first);
  // A movement's duration with practice (trials with the cube it sees).
  double practised(double duration) const { return duration * learnt_.practised_movement; }
  // A part of the grasp (closing, loading, lift) at the pace its caution lets practice give:
  // `practice` the factor practice alone would apply.
  double grasp_paced(double duration, double practice) const;
  // A grasp that failed (a closing that missed the cube, a cube lost under load): the grasps
  // after it slow down.
  void grasp_failed();
  double lift_time() const;  // the lift off the floor, one bit of Fitts' law, grasp-paced
  double peak_aperture(double cube_size) const;
  double fitts(double distance, double width) const;
  double correction(double distance, double width) const;
  void move_grip(const Eigen::Vector3d& target, double duration, bool noisy);
  void move_aperture(double target, double duration);
  void plan_reach(const Observation& o, const Seen& s);
  // Opens and goes for the cube again.
  void start_regrasp();
  // The cube was lost from the pads under load (lifted, carried or lowered): a failed grasp,
  // and its grip margin or its pads' height moved as what it saw shows; then it goes for the
  // cube again.
  void slipped(const Observation& o, const Seen& s);
  static double margin_within(double margin, double cube_size);
  double lower_within(double lower) const;
  // The end of a closing's look for contact: the aperture where it first saw a pad on the
  // cube against where it expected one (none: no pad touched), which it adapts to at once.
  void closing_contact(const std::optional<double>& error);
  // Where it saw its pads' midpoint against the cube's centre as a pad first touched it: the
  // aim's error, which it adapts to at once (a closing in which no pad touched leaves the aim
  // as it was). The servo follows the new aim for the rest of this closing too.
  void closing_aim(const Eigen::Vector3d& error);
  void update(const Observation* o);
  // What it sees beyond the phase it is in.
  void learn_gain(const Observation& o, const Seen& s);
  void servo(const Observation& o, const Seen& s);
  bool watch_for_caught_cube(const Observation* o, const Seen& s);
  bool loss_seen(const Observation* o, const Seen& s) const;
  // One function per phase; each may move to the next.
  void check_reach(const Observation& o, const Seen& s);
  void check_descent(const Observation& o, const Seen& s);
  void close(const Observation* o, const Seen& s);
  void confirm(const Observation* o, const Seen& s);
  void check_lift(const Observation& o, const Seen& s);
  void aim_transport(const Observation& o, const Seen& s, bool first);
  void lower(const Observation* o, const Seen& s);
  void wait_rest(const Observation& o, const Seen& s);
  void withdraw(const Observation* o, const Seen& s);
  void free_cube(const Observation& o, const Seen& s, bool caught);

  const Behaviour& behaviour() const { return person_.behaviour; }

  SimulatedPerson person_;
  const OwnHand& hand_;
  SeenTrial trial_;
  ParticipantMemory memory_;
  MotorRandom random_;
  double dt_;
  double time_ = 0.0;
  long frame_ = 0;
  std::deque<Observation> shown_;
  std::deque<OwnState> history_;
  TrialLearning learnt_;
  MovementPlan plan_;
  PhaseState phase_;
  TrialExperience experience_;
  Seen last_seen_;
};

}  // namespace handlab::studies
