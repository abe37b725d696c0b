#include "studies/participant/simulated_participant.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "studies/participant/behaviour.h"

namespace handlab::studies {
namespace {

Eigen::Vector3d horizontal(const Eigen::Vector3d& v) {
  return Eigen::Vector3d(v.x(), 0, v.z());
}

Eigen::Vector3d up(double height) {
  return Eigen::Vector3d(0, height, 0);
}

}  // namespace

SimulatedParticipant::SimulatedParticipant(const SimulatedPerson& person, const OwnHand& hand,
                                           const SeenTrial& trial, ParticipantMemory memory)
    : person_(person),
      hand_(hand),
      trial_(trial),
      memory_(std::move(memory)),
      random_(person.seed ^ (0xBF58476D1CE4E5B9ull * std::uint64_t(trial.position + 1))),
      dt_(1.0 / trial.rate_hz) {
  const MotorParameters& m = person_.motor;
  // Practice shortens what every trial shares with the trials done.
  learnt_.practised_general =
      practice_factor(memory_.trials + 1, m.practice_rate, m.practice_floor);
  plan_.reaction_time = learnt_.practised_general *
                        random_.ex_gaussian(m.reaction_mu, m.reaction_sigma, m.reaction_tau);
  for (int i = 0; i < 3; ++i) plan_.tremor_phase[i] = 2 * std::numbers::pi * random_.uniform();
}

const char* SimulatedParticipant::phase_name() const {
  static const char* names[] = {"react",         "reach",      "check reach", "descend",
                                "check descent", "close",      "slow close",  "confirm",
                                "lift",          "check lift", "transport",   "check transport",
                                "lower",         "release",    "wait rest",   "withdraw",
                                "reopen",        "free cube",  "idle"};
  return names[int(phase_.phase)];
}

Activity SimulatedParticipant::activity() const {
  switch (phase_.phase) {
    case Phase::kReact:
      return Activity::kReact;
    case Phase::kReach:
    case Phase::kCheckReach:
      return Activity::kReach;
    case Phase::kDescend:
    case Phase::kCheckDescent:
      return Activity::kDescend;
    case Phase::kClose:
    case Phase::kSlowClose:
    case Phase::kConfirm:
      return Activity::kClose;
    case Phase::kLift:
    case Phase::kCheckLift:
      return Activity::kLift;
    case Phase::kTransport:
    case Phase::kCheckTransport:
      return Activity::kTransport;
    case Phase::kLower:
    case Phase::kRelease:
    case Phase::kWaitRest:
      return Activity::kSetDown;
    case Phase::kWithdraw:
    case Phase::kIdle:
      return Activity::kWithdraw;
    case Phase::kReopen:
      return Activity::kReopen;
    case Phase::kFreeCube:
      return Activity::kFreeCube;
  }
  return Activity::kReact;
}

ParticipantMemory SimulatedParticipant::memory_after() const {
  return remember(memory_, experience_, person_.motor.contact_rates, person_.motor.grip_retention);
}

const Observation* SimulatedParticipant::delayed() const {
  const Observation* found = nullptr;
  for (const Observation& o : shown_)
    if (o.time <= time_ - person_.motor.visual_delay + 1e-9) found = &o;
  return found;
}

SimulatedParticipant::OwnState SimulatedParticipant::own_at(double time) const {
  OwnState found = history_.empty() ? OwnState{0, Eigen::Vector3d::Zero(), 0} : history_.front();
  for (const OwnState& s : history_)
    if (s.time <= time + 1e-9) found = s;
  return found;
}

SimulatedParticipant::Seen SimulatedParticipant::see(const Observation& o) const {
  Seen s;
  s.cube = o.cube_position;
  s.both_touching = o.thumb_touching && o.index_touching;
  const SeenHandGeometry& g = trial_.hand;
  if (o.bones.empty() || g.thumb_distal < 0 || g.index_distal < 0) return s;
  // A distal phalanx as it is drawn: a capsule along the bone. What it watches of each is
  // the point of the bone's axis nearest the cube (where that finger will touch), from a
  // fifth of the bone to its tip.
  const Eigen::Matrix3d cube_axes = o.cube_orientation.toRotationMatrix();
  auto nearest_on_bone = [&](int bone) {
    const Eigen::Isometry3d& frame = o.bones[std::size_t(bone)];
    const double length = g.bone_length[std::size_t(bone)];
    const Eigen::Vector3d axis = frame.linear().col(1);
    // In a tip pinch it watches the fingertips themselves.
    const double along =
        plan_.pinch == Pinch::kTip
            ? length
            : std::clamp(axis.dot(o.cube_position - frame.translation()), 0.2 * length, length);
    return Eigen::Vector3d(frame.translation() + along * axis);
  };
  const Eigen::Vector3d thumb = nearest_on_bone(g.thumb_distal);
  const Eigen::Vector3d index = nearest_on_bone(g.index_distal);
  // How far each pad's surface is from the cube: a finger's flesh on the cube shows as
  // touching only where the pad itself is at a face (not a knuckle on the top).
  auto gap = [&](const Eigen::Vector3d& p, int bone) {
    const Eigen::Vector3d local = cube_axes.transpose() * (p - o.cube_position);
    const Eigen::Vector3d nearest = local.cwiseMax(-0.5 * o.cube_size).cwiseMin(0.5 * o.cube_size);
    return (local - nearest).norm() - g.bone_radius[std::size_t(bone)];
  };
  s.thumb_gap = gap(thumb, g.thumb_distal);
  s.index_gap = gap(index, g.index_distal);
  s.thumb_on = o.thumb_touching && s.thumb_gap < behaviour().pad_on_face;
  s.index_on = o.index_touching && s.index_gap < behaviour().pad_on_face;
  s.both_touching = s.thumb_on && s.index_on;
  s.hand = true;
  s.grip = 0.5 * (thumb + index);
  s.aperture = (thumb - index).norm() - g.bone_radius[std::size_t(g.thumb_distal)] -
               g.bone_radius[std::size_t(g.index_distal)];
  return s;
}

// Where it aims the contact points' midpoint: over the cube's centre, shifted by what its
// earlier closings taught it of where its pads end up; in a pad pinch near the top of the
// (large) cube so that the curled fingers clear it, in a tip pinch at the (small) cube's
// mid-height, where the fingertips press on its faces and not under its edges.
Eigen::Vector3d SimulatedParticipant::grasp_point(const Observation& o) const {
  const double side = o.cube_size;
  const double bottom = o.cube_position.y() - 0.5 * side;
  const double height =
      (plan_.pinch == Pinch::kTip ? 0.5 * side : std::max(0.4 * side, side - 0.012)) -
      learnt_.grasp_lower;
  return Eigen::Vector3d(o.cube_position.x() - learnt_.aim_x.correction(), bottom + height,
                         o.cube_position.z() - learnt_.aim_z.correction());
}

bool SimulatedParticipant::cube_at_rest(const Seen& s) {
  if (phase_.resting_since < 0 || (s.cube - phase_.resting_at).norm() > behaviour().rest_travel) {
    phase_.resting_since = time_;
    phase_.resting_at = s.cube;
    return false;
  }
  return time_ - phase_.resting_since >= behaviour().rest_look;
}

bool SimulatedParticipant::in_zone_b(const Seen& s, const Observation& o) {
  const Eigen::Vector3d off = horizontal(s.cube - o.zone_b);
  return std::abs(off.x()) < 0.5 * o.zone_size && std::abs(off.z()) < 0.5 * o.zone_size;
}

double SimulatedParticipant::clearance(const Seen& s, const Observation& o) const {
  return std::max(s.aperture - o.cube_size, behaviour().min_clearance);
}

double SimulatedParticipant::aperture_now() const {
  const double u =
      plan_.aperture_duration > 0 ? (time_ - plan_.aperture_start) / plan_.aperture_duration : 1.0;
  return plan_.aperture_from + minimum_jerk(u) * (plan_.aperture_to - plan_.aperture_from);
}

// Its own hand's opening: the margin over the object scales with the hand (body-scaled
// prehension), the object's share with the object.
double SimulatedParticipant::peak_aperture(double cube_size) const {
  const MotorParameters& m = person_.motor;
  return m.aperture_intercept * person_.participant.hand_length /
             behaviour().reference_hand_length +
         m.aperture_slope * cube_size;
}

double SimulatedParticipant::grasp_paced(double duration, double practice) const {
  return duration * (practice + std::min(learnt_.caution, 1.0) * (1 - practice));
}

double SimulatedParticipant::lift_time() const {
  const double height = behaviour().lift_height;
  return grasp_paced(fitts_time(person_.motor.fitts_a, person_.motor.fitts_b, height, height),
                     learnt_.practised_movement);
}

void SimulatedParticipant::grasp_failed() {
  // Post-error slowing (Rabbitt 1966): the grasps after a failed one give back practice's
  // speed-up, as people trade speed for accuracy by what errors cost them (Dean, Wu &
  // Maloney 2007).
  learnt_.caution += person_.motor.post_error_caution;
  experience_.caution_added += person_.motor.post_error_caution;
}

double SimulatedParticipant::fitts(double distance, double width) const {
  return practised(fitts_time(person_.motor.fitts_a, person_.motor.fitts_b, distance, width));
}

// A corrective submovement continues the movement under way: it pays Fitts' slope for its
// own amplitude and tolerance, not the intercept of starting a movement.
double SimulatedParticipant::correction(double distance, double width) const {
  return practised(fitts_time(0.0, person_.motor.fitts_b, distance, width));
}

void SimulatedParticipant::move_grip(const Eigen::Vector3d& target, double duration, bool noisy) {
  const Eigen::Vector3d now = plan_.grip.at(time_) + plan_.servo;
  plan_.servo.setZero();
  Eigen::Vector3d end = target;
  if (noisy) {
    const MotorParameters& m = person_.motor;
    end += random_.normal3(m.noise_constant + m.noise_proportional * (target - now).norm());
  }
  plan_.grip = MinimumJerkMove{now, end, time_, std::max(duration, dt_)};
}

void SimulatedParticipant::move_aperture(double target, double duration) {
  plan_.aperture_from = aperture_now();
  plan_.aperture_to =
      std::clamp(target, hand_.min_aperture(plan_.pinch), hand_.max_aperture(plan_.pinch));
  plan_.aperture_start = time_;
  plan_.aperture_duration = std::max(duration, dt_);
}

void SimulatedParticipant::plan_reach(const Observation& o, const Seen& s) {
  const Eigen::Vector3d target_seen = grasp_point(o) + up(behaviour().approach_height);
  const Eigen::Vector3d offset =
      s.hand ? Eigen::Vector3d(s.grip - own_at(o.time).grip) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d target = target_seen - offset;
  // The hand must end with the open pads either side of the cube: the clearance they leave
  // is the reach's tolerance.
  const double duration =
      fitts((target - (plan_.grip.at(time_) + plan_.servo)).norm(),
            std::max(peak_aperture(o.cube_size) - o.cube_size, behaviour().min_clearance));
  move_grip(target, duration, true);
  move_aperture(peak_aperture(o.cube_size), person_.motor.peak_aperture_at * duration);
  plan_.corrections_this_move = 0;
  plan_.servo_on = false;
  phase_.phase = Phase::kReach;
}

void SimulatedParticipant::slipped(const Observation& o, const Seen& s) {
  ++experience_.losses;
  ++experience_.slips;
  ++experience_.time.slips;
  grasp_failed();
  // What it saw tells it what went wrong. Pads that came together where the cube was slid
  // over it: it places them lower on the cube the next time (digit placement is learnt from
  // the lifts before: Lukos, Ansuini & Santello 2007; Fu, Zhang & Santello 2010). Pads that
  // stayed apart let it go: it grips harder (Johansson & Westling 1984). A closing that missed
  // or a cube that came to rest outside B says nothing of either.
  if (s.hand && s.aperture < o.cube_size) {
    const double lower = lower_within(learnt_.grasp_lower + person_.motor.regrasp_lower);
    experience_.lowered += lower - learnt_.grasp_lower;
    learnt_.grasp_lower = lower;
  } else {
    const double margin =
        margin_within(learnt_.extra_squeeze + person_.motor.regrasp_squeeze, o.cube_size);
    experience_.squeeze_added += margin - learnt_.extra_squeeze;
    learnt_.extra_squeeze = margin;
  }
  start_regrasp();
}

// It closes on after contact by at most half the cube's side (a margin carried whole with no
// bound ran to 236 mm in a draft of model 2.5), and grasps at most one step lower than it
// first chose (a draft that lowered by up to a quarter of the side lost the 6 cm cube 58 times
// where model 2.6 lost it 30 times, in the same probe).
double SimulatedParticipant::margin_within(double margin, double cube_size) {
  return std::clamp(margin, 0.0, 0.5 * cube_size);
}

double SimulatedParticipant::lower_within(double lower) const {
  return std::clamp(lower, 0.0, person_.motor.regrasp_lower);
}

void SimulatedParticipant::start_regrasp() {
  plan_.servo_on = false;
  const double cube = shown_.empty() ? 0.0 : shown_.back().cube_size;
  move_aperture(peak_aperture(cube), practised(behaviour().reopen_time));
  move_grip(plan_.grip.at(time_) + plan_.servo + up(behaviour().approach_height),
            practised(behaviour().reopen_rise_time), false);
  phase_.phase = Phase::kReopen;
}

// How the seen aperture follows its own, learnt while the virtual fingers touch nothing.
void SimulatedParticipant::learn_gain(const Observation& o, const Seen& s) {
  if (!s.hand || o.thumb_touching || o.index_touching) return;
  const OwnState own = own_at(o.time);
  if (own.aperture <= behaviour().gain_min_aperture) return;
  const double g = s.aperture / own.aperture;
  learnt_.gain_estimate = learnt_.gain_samples++ == 0
                              ? g
                              : (1 - behaviour().gain_smoothing) * learnt_.gain_estimate +
                                    behaviour().gain_smoothing * g;
}

// Continuous correction of the grip towards the grasp point it sees (the descent's own plan
// sets the height).
void SimulatedParticipant::servo(const Observation& o, const Seen& s) {
  if (!plan_.servo_on || !s.hand) return;
  const Eigen::Vector3d offset = s.grip - own_at(o.time).grip;
  Eigen::Vector3d error = grasp_point(o) - offset - (plan_.grip.to + plan_.servo);
  error.y() = 0;
  plan_.servo += behaviour().servo_gain * dt_ * error;
}

// A cube it sees caught on the hand while it goes for the cube (stuck to a fingertip, in a
// finger's crease): reaching for it would carry it along. It opens the hand wide for the
// cube to fall, then looks again (kFreeCube). True when it starts doing so.
bool SimulatedParticipant::watch_for_caught_cube(const Observation* o, const Seen& s) {
  if (o && s.hand && !s.both_touching &&
      s.cube.y() - 0.5 * o->cube_size > behaviour().caught_height) {
    if (phase_.off_floor_since < 0) phase_.off_floor_since = time_;
  } else if (o) {
    phase_.off_floor_since = -1;
  }
  phase_.caught =
      phase_.off_floor_since >= 0 && time_ - phase_.off_floor_since >= behaviour().caught_look;
  const bool going_for_cube = phase_.phase == Phase::kReach || phase_.phase == Phase::kCheckReach ||
                              phase_.phase == Phase::kDescend ||
                              phase_.phase == Phase::kCheckDescent ||
                              phase_.phase == Phase::kReopen;
  if (!going_for_cube || !phase_.caught) return false;
  ++experience_.corrections;
  phase_.wipes = 0;
  plan_.servo_on = false;
  move_grip(plan_.grip.at(time_) + plan_.servo, dt_, false);  // it stops where it is
  move_aperture(hand_.max_aperture(plan_.pinch), practised(behaviour().reopen_time));
  phase_.phase = Phase::kFreeCube;
  return true;
}

bool SimulatedParticipant::loss_seen(const Observation* o, const Seen& s) const {
  return o && s.hand && (s.cube - s.grip).norm() > 0.5 * o->cube_size + behaviour().loss_distance;
}

void SimulatedParticipant::check_reach(const Observation& o, const Seen& s) {
  const Eigen::Vector3d error = grasp_point(o) + up(behaviour().approach_height) - s.grip;
  const double tolerance =
      std::max(behaviour().min_tolerance, behaviour().reach_tolerance_share * clearance(s, o));
  if (s.hand && error.norm() > tolerance &&
      plan_.corrections_this_move < behaviour().max_corrections) {
    ++plan_.corrections_this_move;
    ++experience_.corrections;
    move_grip(plan_.grip.at(time_) + plan_.servo + error, correction(error.norm(), 2 * tolerance),
              true);
    phase_.phase = Phase::kReach;
    return;
  }
  const Eigen::Vector3d offset =
      s.hand ? Eigen::Vector3d(s.grip - own_at(o.time).grip) : Eigen::Vector3d::Zero();
  const double descent = fitts(behaviour().approach_height, clearance(s, o));
  move_grip(grasp_point(o) - offset, descent, true);
  // After its peak the grip closes while the hand comes down, to a little wider than the
  // cube it sees, so that the final closing is short.
  move_aperture((o.cube_size + 2 * behaviour().pre_contact_margin) /
                    std::max(learnt_.gain_estimate, behaviour().min_gain),
                descent);
  plan_.servo_on = true;
  plan_.corrections_this_move = 0;
  phase_.phase = Phase::kDescend;
}

void SimulatedParticipant::check_descent(const Observation& o, const Seen& s) {
  // The fingers straddle the cube: are they centred on its aim, and low enough on its faces? A
  // corrective submovement if not (the precision the closing needs: a share of the room the
  // pads have, the cube's side across, the grasp's depth below the top edge up and down).
  const Eigen::Vector3d target = grasp_point(o);
  const Eigen::Vector3d error = target - s.grip;
  const double share = behaviour().centring_tolerance_share;
  const double across = std::max(behaviour().min_tolerance, share * o.cube_size);
  const double depth = o.cube_position.y() + 0.5 * o.cube_size - target.y();
  const double vertical = std::max(behaviour().min_tolerance, share * depth);
  if (s.hand && (horizontal(error).norm() > across || std::abs(error.y()) > vertical) &&
      plan_.corrections_this_move < behaviour().max_corrections) {
    ++plan_.corrections_this_move;
    ++experience_.corrections;
    move_grip(plan_.grip.at(time_) + plan_.servo + error,
              correction(error.norm(), 2 * std::min(across, vertical)), true);
    phase_.phase = Phase::kDescend;
    return;
  }
  ++experience_.grasp_attempts;
  // Where it expects a pad to meet the cube: the seen size through its estimate of how the
  // seen fingers follow its own, with what its earlier closings taught it; it aims just past
  // that, so that the digits arrive at the cube as their movement ends (Smeets & Brenner 1999).
  // The grip a slip taught it is added once the pads touch (the loading phase): grip force
  // builds up after contact (Johansson & Westling 1984), not in the transport of the digits.
  learnt_.expected_contact = o.cube_size / std::max(learnt_.gain_estimate, behaviour().min_gain) +
                             learnt_.contact.correction();
  phase_.closing_touched = false;
  move_aperture(learnt_.expected_contact - behaviour().closing_past_contact,
                grasp_paced(person_.motor.closing_time, learnt_.practised_movement));
  phase_.phase = Phase::kClose;
}

void SimulatedParticipant::closing_contact(const std::optional<double>& error) {
  experience_.contact_errors.push_back(error);
  learnt_.contact = after_closing(learnt_.contact, error, person_.motor.contact_rates);
}

void SimulatedParticipant::closing_aim(const Eigen::Vector3d& error) {
  experience_.aim_errors.push_back({error.x(), error.z()});
  learnt_.aim_x = adapt(learnt_.aim_x, person_.motor.contact_rates, error.x());
  learnt_.aim_z = adapt(learnt_.aim_z, person_.motor.contact_rates, error.z());
}

void SimulatedParticipant::close(const Observation* o, const Seen& s) {
  // The first pad seen on the cube: what its own aperture was there tells it how far off its
  // expectation was, for its next closing.
  if (o && !phase_.closing_touched && (s.thumb_on || s.index_on)) {
    phase_.closing_touched = true;
    closing_contact(own_at(o->time).aperture - learnt_.expected_contact);
    closing_aim(s.grip - s.cube);
  }
  if (o && s.both_touching) {
    // Build up the grip (the loading phase) from where the hand is.
    move_aperture(aperture_now() - behaviour().grip_loading - learnt_.extra_squeeze,
                  grasp_paced(person_.motor.confirm_dwell, learnt_.practised_general));
    phase_.touching_since = time_;
    phase_.phase = Phase::kConfirm;
    return;
  }
  if (phase_.phase == Phase::kClose && time_ >= plan_.aperture_start + plan_.aperture_duration)
    phase_.phase = Phase::kSlowClose;
  if (phase_.phase != Phase::kSlowClose) return;
  const double now = plan_.aperture_to;
  if (now <= hand_.min_aperture(plan_.pinch) + 1e-4) {
    ++experience_.time.missed_closings;
    if (!phase_.closing_touched) closing_contact(std::nullopt);
    grasp_failed();
    start_regrasp();
    return;
  }
  plan_.aperture_from = plan_.aperture_to =
      std::max(now - behaviour().slow_closing * dt_, hand_.min_aperture(plan_.pinch));
  plan_.aperture_duration = 0.0;
}

void SimulatedParticipant::confirm(const Observation* o, const Seen& s) {
  if (o && !s.both_touching) {
    phase_.touching_since = -1;
    phase_.phase = Phase::kSlowClose;
    return;
  }
  if (time_ - phase_.touching_since <
      grasp_paced(person_.motor.confirm_dwell, learnt_.practised_general))
    return;
  plan_.servo_on = false;
  move_grip(plan_.grip.at(time_) + plan_.servo + up(behaviour().lift_height), lift_time(), false);
  phase_.phase = Phase::kLift;
}

void SimulatedParticipant::check_lift(const Observation& o, const Seen& s) {
  if (loss_seen(&o, s) || s.cube.y() - 0.5 * o.cube_size < 0.5 * behaviour().lift_height) {
    slipped(o, s);
    return;
  }
  aim_transport(o, s, true);
}

// To over B, or a correction of the cube's place there; then down to set it on the floor.
void SimulatedParticipant::aim_transport(const Observation& o, const Seen& s, bool first) {
  if (first) plan_.corrections_this_move = 0;
  // The cube it sees, moved on by what its hand did since.
  const Eigen::Vector3d own_now = plan_.grip.at(time_) + plan_.servo;
  const Eigen::Vector3d cube_now = s.cube + (own_now - own_at(o.time).grip);
  const Eigen::Vector3d error = horizontal(o.zone_b - cube_now);
  const double tolerance =
      std::max(behaviour().placement_tolerance,
               0.5 * (o.zone_size - o.cube_size) - behaviour().placement_margin);
  if (first ||
      (error.norm() > tolerance && plan_.corrections_this_move < behaviour().max_corrections)) {
    if (!first) {
      ++plan_.corrections_this_move;
      ++experience_.corrections;
    }
    move_grip(own_now + error,
              first ? fitts(error.norm(), o.zone_size) : correction(error.norm(), 2 * tolerance),
              true);
    phase_.phase = Phase::kTransport;
    return;
  }
  const double drop = cube_now.y() - (0.5 * o.cube_size - behaviour().place_depth);
  // Down onto the floor, which stops the cube: no endpoint to hit (one bit, as the lift).
  move_grip(own_now - up(drop), fitts(std::abs(drop), std::abs(drop)), false);
  phase_.phase = Phase::kLower;
}

void SimulatedParticipant::lower(const Observation* o, const Seen& s) {
  if (loss_seen(o, s)) {
    slipped(*o, s);
  } else if (plan_.grip.done(time_)) {
    // Let go: the hand opens at least to its peak aperture, so that no finger stays hooked
    // on a large cube.
    const double cube = shown_.empty() ? 0.0 : shown_.back().cube_size;
    move_aperture(std::max(plan_.aperture_to + behaviour().release_opening, peak_aperture(cube)),
                  practised(behaviour().reopen_time));
    phase_.phase = Phase::kRelease;
  }
}

void SimulatedParticipant::wait_rest(const Observation& o, const Seen& s) {
  if (in_zone_b(s, o)) {
    // Set down where it should be: up and away; out sideways, from under the cube, if the
    // cube came up with the hand before.
    const Eigen::Vector3d own_now = plan_.grip.at(time_) + plan_.servo;
    Eigen::Vector3d away = up(behaviour().withdraw_height);
    if (phase_.slide_out) {
      // Away from the cube as it sees its pads and the cube (one frame, the scene's).
      const Eigen::Vector3d side = s.hand ? horizontal(s.grip - s.cube) : Eigen::Vector3d::Zero();
      away += behaviour().withdraw_height *
              (side.norm() > 1e-6 ? side.normalized() : Eigen::Vector3d::UnitZ());
    }
    move_grip(own_now + away, fitts(away.norm(), behaviour().withdraw_height), false);
    phase_.phase = Phase::kWithdraw;
  } else {
    ++experience_.losses;  // it came to rest outside B: pick it up again
    start_regrasp();
  }
}

void SimulatedParticipant::withdraw(const Observation* o, const Seen& s) {
  // The cube coming up with the hand: still caught on it; put it down, open wide, and next
  // time slide the hand out from under it.
  if (o && o->time > plan_.grip.start &&
      s.cube.y() - 0.5 * o->cube_size > behaviour().at_rest_over_floor) {
    ++experience_.corrections;
    phase_.slide_out = true;
    move_grip(plan_.grip.at(time_) + plan_.servo - up(s.cube.y() - 0.5 * o->cube_size),
              practised(behaviour().reopen_time), false);
    move_aperture(hand_.max_aperture(plan_.pinch), practised(behaviour().reopen_time));
    phase_.phase = Phase::kRelease;
  } else if (plan_.grip.done(time_)) {
    phase_.resting_since = -1;
    phase_.phase = Phase::kIdle;
  }
}

// Opened wide: if the cube is still on the hand, it wipes it off on the floor, the hand down
// until the cube would be wipe_depth under it (deeper each time it stays).
void SimulatedParticipant::free_cube(const Observation& o, const Seen& s, bool caught) {
  if (!caught) {
    plan_reach(o, s);
    return;
  }
  ++experience_.corrections;
  ++phase_.wipes;
  const double down = s.cube.y() - 0.5 * o.cube_size + phase_.wipes * behaviour().wipe_depth;
  move_grip(plan_.grip.at(time_) + plan_.servo - up(down), fitts(down, o.cube_size), false);
}

void SimulatedParticipant::update(const Observation* o) {
  const double t = time_;
  Seen s;
  if (o) s = see(*o);
  last_seen_ = s;
  const double aperture_end = plan_.aperture_start + plan_.aperture_duration;
  const double grip_end = plan_.grip.start + plan_.grip.duration;
  if (o) learn_gain(*o, s);
  if (o) servo(*o, s);
  if (watch_for_caught_cube(o, s)) return;
  // Where a phase waits for the look at the end of a movement: the observation must show
  // the moment it ended.
  const bool looked = o && o->time >= grip_end;
  switch (phase_.phase) {
    case Phase::kReact:
      if (t >= plan_.reaction_time && o) plan_reach(*o, s);
      break;
    case Phase::kReach:
      if (plan_.grip.done(t)) phase_.phase = Phase::kCheckReach;
      break;
    case Phase::kCheckReach:
      if (looked) check_reach(*o, s);
      break;
    case Phase::kDescend:
      if (plan_.grip.done(t)) phase_.phase = Phase::kCheckDescent;
      break;
    case Phase::kCheckDescent:
      if (looked) check_descent(*o, s);
      break;
    case Phase::kClose:
    case Phase::kSlowClose:
      close(o, s);
      break;
    case Phase::kConfirm:
      confirm(o, s);
      break;
    case Phase::kLift:
    case Phase::kTransport:
      if (loss_seen(o, s)) {
        slipped(*o, s);
      } else if (plan_.grip.done(t)) {
        phase_.phase = phase_.phase == Phase::kLift ? Phase::kCheckLift : Phase::kCheckTransport;
      }
      break;
    case Phase::kCheckLift:
      if (looked) check_lift(*o, s);
      break;
    case Phase::kCheckTransport:
      if (!looked) break;
      if (loss_seen(o, s)) {
        slipped(*o, s);
      } else {
        aim_transport(*o, s, false);
      }
      break;
    case Phase::kLower:
      lower(o, s);
      break;
    case Phase::kRelease:
      if (t >= aperture_end) {
        phase_.resting_since = -1;
        phase_.phase = Phase::kWaitRest;
      }
      break;
    case Phase::kWaitRest:
      if (o && o->time >= aperture_end && cube_at_rest(s)) wait_rest(*o, s);
      break;
    case Phase::kWithdraw:
      withdraw(o, s);
      break;
    case Phase::kReopen:
      if (plan_.grip.done(t) && t >= aperture_end && looked) plan_reach(*o, s);
      break;
    case Phase::kFreeCube:
      if (plan_.grip.done(t) && t >= aperture_end && o &&
          o->time >= std::max(grip_end, aperture_end))
        free_cube(*o, s, phase_.caught);
      break;
    case Phase::kIdle:
      // The trial goes on, so the cube it left in B has slid out of it: it goes back for it.
      if (o && cube_at_rest(s) && !in_zone_b(s, *o)) {
        ++experience_.losses;
        start_regrasp();
      }
      break;
  }
}

void SimulatedParticipant::start(const Observation& first) {
  const MotorParameters& m = person_.motor;
  // At rest before the trial: over the near side of A, the fingers loosely open.
  const Eigen::Vector3d home =
      first.zone_a + Eigen::Vector3d(0, behaviour().home_height, behaviour().home_back);
  plan_.pinch = first.cube_size < behaviour().tip_pinch_below ? Pinch::kTip : Pinch::kPad;
  plan_.grip = MinimumJerkMove{home, home, 0.0, dt_};
  plan_.aperture_from = plan_.aperture_to = behaviour().rest_aperture;
  experience_.cube_size = first.cube_size;
  // What it remembers of this cube: practice with it, where its pads met it and where they
  // ended up against it (offsets, which people carry over; a changed gain between seen and
  // felt size they do not: Safstrom & Edin 2005), the grip margin and the pads' height its
  // slips taught it.
  const CubeMemory* cube = memory_.cube(first.cube_size);
  learnt_.practised_movement =
      practice_factor((cube ? cube->trials : 0) + 1, m.practice_rate, m.practice_floor);
  if (cube) {
    learnt_.contact = cube->contact;
    learnt_.aim_x = cube->aim_x;
    learnt_.aim_z = cube->aim_z;
    learnt_.extra_squeeze = margin_within(cube->grip_margin, first.cube_size);
    learnt_.grasp_lower = lower_within(cube->grasp_lower);
    learnt_.caution = std::max(0.0, cube->caution.correction());
  }
  // What it expects the trial to take: its own plan without errors.
  const double cube_size = first.cube_size;
  experience_.expected_time =
      learnt_.practised_general * (m.reaction_mu + m.reaction_tau) +
      fitts((first.zone_a - home).norm(),
            std::max(peak_aperture(cube_size) - cube_size, behaviour().min_clearance)) +
      fitts(behaviour().approach_height, peak_aperture(cube_size) - cube_size) +
      grasp_paced(m.closing_time, learnt_.practised_movement) +
      grasp_paced(m.confirm_dwell, learnt_.practised_general) + lift_time() +
      fitts((first.zone_b - first.zone_a).norm(), first.zone_size) +
      fitts(behaviour().lift_height, behaviour().lift_height);
}

tracking::TrackedFrame SimulatedParticipant::act(const Observation& shown) {
  const MotorParameters& m = person_.motor;
  ++frame_;
  time_ = double(frame_) * dt_;
  if (frame_ == 1) start(shown);
  shown_.push_back(shown);
  // Keep what a delay (and the one before, for speeds) still needs.
  while (shown_.size() > 3 && shown_[2].time <= time_ - m.visual_delay) shown_.pop_front();
  update(delayed());
  experience_.time[activity()] += dt_;

  const double aperture = aperture_now();
  const Eigen::Vector3d grip = plan_.grip.at(time_) + plan_.servo;
  history_.push_back({time_, grip, aperture});
  while (history_.size() > 2 && history_[1].time <= time_ - m.visual_delay - 2 * dt_)
    history_.pop_front();

  Eigen::Vector3d tremor;
  for (int i = 0; i < 3; ++i)
    tremor[i] = std::sqrt(2.0) * m.tremor_rms *
                std::sin(2 * std::numbers::pi * m.tremor_hz * time_ + plan_.tremor_phase[i]);
  std::vector<Eigen::Vector3d> jitter(25);
  for (Eigen::Vector3d& j : jitter) j = random_.normal3(m.tracker_jitter);
  return hand_.frame(hand_.pose(plan_.pinch, grip + tremor, aperture), time_, frame_, jitter);
}

}  // namespace handlab::studies
