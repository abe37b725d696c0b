#include "studies/participant/simulated_participant.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace handlab::studies {
namespace {

constexpr double kApproachHeight = 0.04;  // m above the grasp point before coming down
constexpr double kLiftHeight = 0.08;      // m
constexpr double kWithdrawHeight = 0.10;  // m
// m: it sets the cube down until it sees it on the floor, aiming this far past (the cube stops
// there and the pads slide on it), so that the floor holds it as the fingers open.
constexpr double kPlaceDepth = 0.001;
constexpr double kReleaseOpening = 0.03;  // m the aperture opens to let go
constexpr double kSlowClosing = 0.02;     // m/s when the planned closing did not reach the cube
constexpr double kServoGain = 3.0;        // 1/s, continuous visual correction
constexpr int kMaxCorrections = 3;        // corrective submovements per aimed movement
// The cube looks at rest when it stays within kRestTravel of where it was for kRestLook: a
// person sees whether it still slides or tumbles, not a fingertip's tremor nudging it.
constexpr double kRestTravel = 0.002;          // m
constexpr double kRestLook = 0.2;              // s
constexpr double kPreContactMargin = 0.015;    // m each side of the cube before the closing
constexpr double kClosingPastContact = 0.003;  // m the closing aims past the seen size
constexpr double kGripLoading = 0.003;   // m it closes on after seeing contact (loading phase)
constexpr double kTipPinchBelow = 0.02;  // m: a cube this small is picked with the tips
constexpr double kPadOnFace = 0.007;     // m: a pad's bone this close (surface) is on the cube
// A cube seen this high for this long without both pads on it is caught on the hand (a
// dropped cube falls from the lift's height in a seventh of a second).
constexpr double kCaughtHeight = 0.02;  // m
constexpr double kCaughtLook = 0.2;     // s
constexpr double kWipeDepth = 0.01;     // m under the floor it takes a caught cube to wipe it off

Eigen::Vector3d horizontal(const Eigen::Vector3d& v) {
  return Eigen::Vector3d(v.x(), 0, v.z());
}

}  // namespace

SimulatedParticipant::SimulatedParticipant(const SimulatedPerson& person, const OwnHand& hand,
                                           TrialContext context)
    : person_(person),
      hand_(hand),
      context_(std::move(context)),
      random_(person.seed ^ (0xBF58476D1CE4E5B9ull * std::uint64_t(context_.position + 1))),
      dt_(1.0 / context_.rate_hz) {
  const MotorParameters& m = person_.motor;
  reaction_time_ = random_.ex_gaussian(m.reaction_mu, m.reaction_sigma, m.reaction_tau);
  for (int i = 0; i < 3; ++i) tremor_phase_[i] = 2 * std::numbers::pi * random_.uniform();
}

const char* SimulatedParticipant::phase_name() const {
  static const char* names[] = {"react",         "reach",      "check reach", "descend",
                                "check descent", "close",      "slow close",  "confirm",
                                "lift",          "check lift", "transport",   "check transport",
                                "lower",         "release",    "wait rest",   "withdraw",
                                "reopen",        "free cube",  "idle"};
  return names[int(phase_)];
}

double SimulatedParticipant::practice() const {
  return std::pow(double(std::max(context_.repetition, 1)), -person_.motor.practice_exponent);
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
  const SeenHandGeometry& g = context_.hand;
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
        pinch_ == Pinch::kTip
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
  s.both_touching = s.both_touching && s.thumb_gap < kPadOnFace && s.index_gap < kPadOnFace;
  s.hand = true;
  s.grip = 0.5 * (thumb + index);
  s.aperture = (thumb - index).norm() - g.bone_radius[std::size_t(g.thumb_distal)] -
               g.bone_radius[std::size_t(g.index_distal)];
  return s;
}

// Where it aims the contact points' midpoint: over the cube's centre; in a pad pinch near the
// top of the (large) cube so that the curled fingers clear it, in a tip pinch at the (small)
// cube's mid-height, where the fingertips press on its faces and not under its edges.
Eigen::Vector3d SimulatedParticipant::grasp_point(const Observation& o) const {
  const double side = o.cube_size;
  const double bottom = o.cube_position.y() - 0.5 * side;
  const double height = pinch_ == Pinch::kTip ? 0.5 * side : std::max(0.4 * side, side - 0.012);
  return Eigen::Vector3d(o.cube_position.x(), bottom + height, o.cube_position.z());
}

bool SimulatedParticipant::cube_at_rest(const Seen& s) {
  if (resting_since_ < 0 || (s.cube - resting_at_).norm() > kRestTravel) {
    resting_since_ = time_;
    resting_at_ = s.cube;
    return false;
  }
  return time_ - resting_since_ >= kRestLook;
}

bool SimulatedParticipant::in_zone_b(const Seen& s, const Observation& o) {
  const Eigen::Vector3d off = horizontal(s.cube - o.zone_b);
  return std::abs(off.x()) < 0.5 * o.zone_size && std::abs(off.z()) < 0.5 * o.zone_size;
}

double SimulatedParticipant::clearance(const Seen& s, const Observation& o) const {
  return std::max(s.aperture - o.cube_size, 0.004);
}

void SimulatedParticipant::move_grip(const Eigen::Vector3d& target, double duration, bool noisy) {
  const Eigen::Vector3d now = grip_.at(time_) + servo_;
  servo_.setZero();
  Eigen::Vector3d end = target;
  if (noisy) {
    const MotorParameters& m = person_.motor;
    end += random_.normal3(m.noise_constant + m.noise_proportional * (target - now).norm());
  }
  grip_ = MinimumJerkMove{now, end, time_, std::max(duration, dt_)};
}

void SimulatedParticipant::move_aperture(double target, double duration) {
  const double u = aperture_duration_ > 0 ? (time_ - aperture_start_) / aperture_duration_ : 1.0;
  const double now = aperture_from_ + minimum_jerk(u) * (aperture_to_ - aperture_from_);
  aperture_from_ = now;
  aperture_to_ = std::clamp(target, hand_.min_aperture(pinch_), hand_.max_aperture(pinch_));
  aperture_start_ = time_;
  aperture_duration_ = std::max(duration, dt_);
}

void SimulatedParticipant::plan_reach(const Observation& o, const Seen& s) {
  const MotorParameters& m = person_.motor;
  const Eigen::Vector3d target_seen = grasp_point(o) + Eigen::Vector3d(0, kApproachHeight, 0);
  const Eigen::Vector3d offset =
      s.hand ? Eigen::Vector3d(s.grip - own_at(o.time).grip) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d target = target_seen - offset;
  const double distance = (target - (grip_.at(time_) + servo_)).norm();
  const double duration = fitts_time(m.fitts_a, m.fitts_b, distance, o.cube_size) * practice();
  move_grip(target, duration, true);
  move_aperture(m.aperture_intercept + m.aperture_slope * o.cube_size,
                m.peak_aperture_at * duration);
  corrections_this_move_ = 0;
  servo_on_ = false;
  phase_ = Phase::kReach;
}

void SimulatedParticipant::start_regrasp() {
  const MotorParameters& m = person_.motor;
  extra_squeeze_ += m.regrasp_squeeze;
  servo_on_ = false;
  const double opening = 0.3 * practice();
  const double cube = shown_.empty() ? 0.0 : shown_.back().cube_size;
  move_aperture(m.aperture_intercept + m.aperture_slope * cube, opening);
  move_grip(grip_.at(time_) + servo_ + Eigen::Vector3d(0, kApproachHeight, 0), 0.4 * practice(),
            false);
  phase_ = Phase::kReopen;
}

void SimulatedParticipant::update(const Observation* o) {
  const MotorParameters& m = person_.motor;
  const double t = time_;
  Seen s;
  if (o) s = see(*o);
  last_seen_ = s;
  const double aperture_end = aperture_start_ + aperture_duration_;
  const double grip_end = grip_.start + grip_.duration;
  // How the seen aperture follows its own, learnt while the virtual fingers touch nothing.
  if (o && s.hand && !o->thumb_touching && !o->index_touching) {
    const OwnState own = own_at(o->time);
    if (own.aperture > 0.03) {
      const double g = s.aperture / own.aperture;
      gain_estimate_ = gain_samples_++ == 0 ? g : 0.95 * gain_estimate_ + 0.05 * g;
    }
  }
  // Continuous correction of the grip towards the grasp point it sees.
  if (servo_on_ && o && s.hand) {
    const Eigen::Vector3d offset = s.grip - own_at(o->time).grip;
    const Eigen::Vector3d desired = grasp_point(*o) - offset;
    const Eigen::Vector3d planned_end = grip_.to + servo_;
    Eigen::Vector3d error = desired - planned_end;
    error.y() = 0;  // the descent's own plan sets the height
    servo_ += kServoGain * dt_ * error;
  }
  auto loss_seen = [&] {
    return o && s.hand && (s.cube - s.grip).norm() > 0.5 * o->cube_size + 0.015;
  };

  // A cube it sees caught on the hand while it goes for the cube (stuck to a fingertip, in a
  // finger's crease): reaching for it would carry it along. It opens the hand wide for the
  // cube to fall, then looks again (kFreeCube).
  if (o && s.hand && !s.both_touching && s.cube.y() - 0.5 * o->cube_size > kCaughtHeight) {
    if (off_floor_since_ < 0) off_floor_since_ = t;
  } else if (o) {
    off_floor_since_ = -1;
  }
  const bool caught = off_floor_since_ >= 0 && t - off_floor_since_ >= kCaughtLook;
  const bool going_for_cube = phase_ == Phase::kReach || phase_ == Phase::kCheckReach ||
                              phase_ == Phase::kDescend || phase_ == Phase::kCheckDescent ||
                              phase_ == Phase::kReopen;
  if (going_for_cube && caught) {
    ++experience_.corrections;
    wipes_ = 0;
    servo_on_ = false;
    move_grip(grip_.at(t) + servo_, dt_, false);  // it stops where it is
    move_aperture(hand_.max_aperture(pinch_), 0.3 * practice());
    phase_ = Phase::kFreeCube;
  }

  switch (phase_) {
    case Phase::kReact:
      if (t >= reaction_time_ && o) plan_reach(*o, s);
      break;
    case Phase::kReach:
      if (grip_.done(t)) phase_ = Phase::kCheckReach;
      break;
    case Phase::kCheckReach: {
      if (!o || o->time < grip_end) break;  // it looks where the movement ended
      const Eigen::Vector3d error =
          grasp_point(*o) + Eigen::Vector3d(0, kApproachHeight, 0) - s.grip;
      const double tolerance = std::max(0.002, 0.25 * clearance(s, *o));
      const Eigen::Vector3d own_now = grip_.at(t) + servo_;
      if (s.hand && error.norm() > tolerance && corrections_this_move_ < kMaxCorrections) {
        ++corrections_this_move_;
        ++experience_.corrections;
        move_grip(own_now + error,
                  fitts_time(m.fitts_a, m.fitts_b, error.norm(), 2 * tolerance) * practice(), true);
        phase_ = Phase::kReach;
        break;
      }
      const Eigen::Vector3d offset =
          s.hand ? Eigen::Vector3d(s.grip - own_at(o->time).grip) : Eigen::Vector3d::Zero();
      const double descent =
          fitts_time(m.fitts_a, m.fitts_b, kApproachHeight, clearance(s, *o)) * practice();
      move_grip(grasp_point(*o) - offset, descent, true);
      // After its peak the grip closes while the hand comes down, to a little wider than the
      // cube it sees, so that the final closing is short.
      move_aperture((o->cube_size + 2 * kPreContactMargin) / std::max(gain_estimate_, 0.3),
                    descent);
      servo_on_ = true;
      corrections_this_move_ = 0;
      phase_ = Phase::kDescend;
      break;
    }
    case Phase::kDescend:
      if (grip_.done(t)) phase_ = Phase::kCheckDescent;
      break;
    case Phase::kCheckDescent: {
      if (!o || o->time < grip_end) break;  // it looks where the descent ended
      // The fingers straddle the cube: are they centred on it? A corrective submovement if
      // not (the precision the closing needs: a quarter of the cube's side).
      const Eigen::Vector3d error = grasp_point(*o) - s.grip;
      const double tolerance = std::max(0.002, 0.25 * o->cube_size);
      if (s.hand && error.norm() > tolerance && corrections_this_move_ < kMaxCorrections) {
        ++corrections_this_move_;
        ++experience_.corrections;
        move_grip(grip_.at(t) + servo_ + error,
                  fitts_time(m.fitts_a, m.fitts_b, error.norm(), 2 * tolerance) * practice(), true);
        phase_ = Phase::kDescend;
        break;
      }
      ++experience_.grasp_attempts;
      {
        const double contact = o->cube_size / std::max(gain_estimate_, 0.3);
        move_aperture(contact - kClosingPastContact - extra_squeeze_, m.closing_time * practice());
      }
      phase_ = Phase::kClose;
      break;
    }
    case Phase::kClose:
    case Phase::kSlowClose: {
      if (o && s.both_touching) {
        // Seen contact: build up the grip (the loading phase) from where the hand is.
        const double u = aperture_duration_ > 0 ? (t - aperture_start_) / aperture_duration_ : 1.0;
        const double now = aperture_from_ + minimum_jerk(u) * (aperture_to_ - aperture_from_);
        move_aperture(now - kGripLoading - extra_squeeze_, m.confirm_dwell);
        touching_since_ = t;
        phase_ = Phase::kConfirm;
        break;
      }
      if (phase_ == Phase::kClose && t >= aperture_end) phase_ = Phase::kSlowClose;
      if (phase_ == Phase::kSlowClose) {
        const double now = aperture_to_;
        if (now <= hand_.min_aperture(pinch_) + 1e-4) {
          start_regrasp();
          break;
        }
        aperture_from_ = aperture_to_ =
            std::max(now - kSlowClosing * dt_, hand_.min_aperture(pinch_));
        aperture_duration_ = 0.0;
      }
      break;
    }
    case Phase::kConfirm:
      if (o && !s.both_touching) {
        touching_since_ = -1;
        phase_ = Phase::kSlowClose;
        break;
      }
      if (t - touching_since_ >= m.confirm_dwell) {
        servo_on_ = false;
        move_grip(grip_.at(t) + servo_ + Eigen::Vector3d(0, kLiftHeight, 0),
                  fitts_time(m.fitts_a, m.fitts_b, kLiftHeight, kLiftHeight) * practice(), false);
        phase_ = Phase::kLift;
      }
      break;
    case Phase::kLift:
    case Phase::kTransport:
      if (loss_seen()) {
        ++experience_.losses;
        start_regrasp();
      } else if (grip_.done(t)) {
        phase_ = phase_ == Phase::kLift ? Phase::kCheckLift : Phase::kCheckTransport;
      }
      break;
    case Phase::kCheckLift: {
      if (!o || o->time < grip_end) break;
      if (loss_seen() || s.cube.y() - 0.5 * o->cube_size < 0.5 * kLiftHeight) {
        ++experience_.losses;
        start_regrasp();
        break;
      }
      [[fallthrough]];
    }
    case Phase::kCheckTransport: {
      if (phase_ == Phase::kCheckTransport) {
        if (!o || o->time < grip_end) break;
        if (loss_seen()) {
          ++experience_.losses;
          start_regrasp();
          break;
        }
      }
      const bool first = phase_ == Phase::kCheckLift;
      if (first) corrections_this_move_ = 0;
      // The cube it sees, moved on by what its hand did since.
      const Eigen::Vector3d own_now = grip_.at(t) + servo_;
      const Eigen::Vector3d cube_now = s.cube + (own_now - own_at(o->time).grip);
      const Eigen::Vector3d error = horizontal(o->zone_b - cube_now);
      const double tolerance = std::max(0.005, 0.5 * (o->zone_size - o->cube_size) - 0.01);
      if (first || (error.norm() > tolerance && corrections_this_move_ < kMaxCorrections)) {
        if (!first) {
          ++corrections_this_move_;
          ++experience_.corrections;
        }
        const double width = first ? o->zone_size : 2 * tolerance;
        move_grip(own_now + error,
                  fitts_time(m.fitts_a, m.fitts_b, error.norm(), width) * practice(), true);
        phase_ = Phase::kTransport;
        break;
      }
      const double drop = cube_now.y() - (0.5 * o->cube_size - kPlaceDepth);
      move_grip(own_now - Eigen::Vector3d(0, drop, 0),
                fitts_time(m.fitts_a, m.fitts_b, std::abs(drop), o->cube_size) * practice(), false);
      phase_ = Phase::kLower;
      break;
    }
    case Phase::kLower:
      if (loss_seen()) {
        ++experience_.losses;
        start_regrasp();
      } else if (grip_.done(t)) {
        // Let go: the hand opens at least to its peak aperture, so that no finger stays
        // hooked on a large cube.
        move_aperture(std::max(aperture_to_ + kReleaseOpening,
                               m.aperture_intercept + m.aperture_slope * o->cube_size),
                      0.3 * practice());
        phase_ = Phase::kRelease;
      }
      break;
    case Phase::kRelease:
      if (t >= aperture_end) {
        resting_since_ = -1;
        phase_ = Phase::kWaitRest;
      }
      break;
    case Phase::kWaitRest: {
      if (!o || o->time < aperture_end || !cube_at_rest(s)) break;
      if (in_zone_b(s, *o)) {
        move_grip(grip_.at(t) + servo_ + Eigen::Vector3d(0, kWithdrawHeight, 0),
                  fitts_time(m.fitts_a, m.fitts_b, kWithdrawHeight, kWithdrawHeight) * practice(),
                  false);
        phase_ = Phase::kWithdraw;
      } else {
        ++experience_.losses;  // it came to rest outside B: pick it up again
        start_regrasp();
      }
      break;
    }
    case Phase::kWithdraw:
      // The cube coming up with the hand: still caught on it; put it down, open wide.
      if (o && o->time > grip_.start && s.cube.y() - 0.5 * o->cube_size > 0.01) {
        ++experience_.corrections;
        move_grip(grip_.at(t) + servo_ - Eigen::Vector3d(0, s.cube.y() - 0.5 * o->cube_size, 0),
                  0.3 * practice(), false);
        move_aperture(hand_.max_aperture(pinch_), 0.3 * practice());
        phase_ = Phase::kRelease;
      } else if (grip_.done(t)) {
        resting_since_ = -1;
        phase_ = Phase::kIdle;
      }
      break;
    case Phase::kReopen:
      if (!grip_.done(t) || t < aperture_end || !o || o->time < grip_end) break;
      plan_reach(*o, s);
      break;
    case Phase::kFreeCube: {
      if (!grip_.done(t) || t < aperture_end || !o || o->time < std::max(grip_end, aperture_end))
        break;
      if (!caught) {
        plan_reach(*o, s);
        break;
      }
      // Still on the hand, opened wide: it wipes the cube off on the floor, the hand down
      // until the cube would be kWipeDepth under it (deeper each time it stays).
      ++experience_.corrections;
      ++wipes_;
      const double down = s.cube.y() - 0.5 * o->cube_size + wipes_ * kWipeDepth;
      move_grip(grip_.at(t) + servo_ - Eigen::Vector3d(0, down, 0),
                fitts_time(m.fitts_a, m.fitts_b, down, o->cube_size) * practice(), false);
      break;
    }
    case Phase::kIdle:
      // The trial goes on, so the cube it left in B has slid out of it: it goes back for it.
      if (o && cube_at_rest(s) && !in_zone_b(s, *o)) {
        ++experience_.losses;
        start_regrasp();
      }
      break;
  }
}

tracking::TrackedFrame SimulatedParticipant::act(const Observation& shown) {
  const MotorParameters& m = person_.motor;
  ++frame_;
  time_ = double(frame_) * dt_;
  if (frame_ == 1) {
    // At rest before the trial: over the near side of A, the fingers loosely open.
    const Eigen::Vector3d home = shown.zone_a + Eigen::Vector3d(0, 0.15, 0.12);
    pinch_ = shown.cube_size < kTipPinchBelow ? Pinch::kTip : Pinch::kPad;
    grip_ = MinimumJerkMove{home, home, 0.0, dt_};
    aperture_from_ = aperture_to_ = 0.04;
    // What it expects the trial to take: its own plan without errors.
    const double p = practice();
    const double mga = m.aperture_intercept + m.aperture_slope * shown.cube_size;
    experience_.expected_time =
        m.reaction_mu + m.reaction_tau +
        p * (fitts_time(m.fitts_a, m.fitts_b, (shown.zone_a - home).norm(), shown.cube_size) +
             fitts_time(m.fitts_a, m.fitts_b, kApproachHeight, mga - shown.cube_size) +
             m.closing_time + m.confirm_dwell +
             fitts_time(m.fitts_a, m.fitts_b, kLiftHeight, kLiftHeight) +
             fitts_time(m.fitts_a, m.fitts_b, (shown.zone_b - shown.zone_a).norm(),
                        shown.zone_size) +
             fitts_time(m.fitts_a, m.fitts_b, kLiftHeight, shown.cube_size));
  }
  shown_.push_back(shown);
  // Keep what a delay (and the one before, for speeds) still needs.
  while (shown_.size() > 3 && shown_[2].time <= time_ - m.visual_delay) shown_.pop_front();
  update(delayed());

  const double u = aperture_duration_ > 0 ? (time_ - aperture_start_) / aperture_duration_ : 1.0;
  const double aperture = aperture_from_ + minimum_jerk(u) * (aperture_to_ - aperture_from_);
  const Eigen::Vector3d grip = grip_.at(time_) + servo_;
  history_.push_back({time_, grip, aperture});
  while (history_.size() > 2 && history_[1].time <= time_ - m.visual_delay - 2 * dt_)
    history_.pop_front();

  Eigen::Vector3d tremor;
  for (int i = 0; i < 3; ++i)
    tremor[i] = std::sqrt(2.0) * m.tremor_rms *
                std::sin(2 * std::numbers::pi * m.tremor_hz * time_ + tremor_phase_[i]);
  std::vector<Eigen::Vector3d> jitter(25);
  for (Eigen::Vector3d& j : jitter) j = random_.normal3(m.tracker_jitter);
  return hand_.frame(hand_.pose(pinch_, grip + tremor, aperture), time_, frame_, jitter);
}

}  // namespace handlab::studies
