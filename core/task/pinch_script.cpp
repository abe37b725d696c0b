#include "core/task/pinch_script.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/retarget/fingertip_solver.h"
#include "core/sim/contact_forces.h"
#include "core/sim/inverted_tets.h"
#include "core/task/finger_pads.h"
#include "core/task/pinch_clearance.h"
#include "core/task/pinch_posture.h"

namespace handlab::sim {
namespace {

double smooth(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

hand::HandPose blend(const hand::HandPose& a, const hand::HandPose& b, double w) {
  hand::HandPose q = a;
  q.angles = a.angles + w * (b.angles - a.angles);
  return q;
}

// The closing's timing: its speed sets the closing's length (the pads travel from 15 mm off
// the faces to their targets), one digit's lead delays the other's degrees of freedom, and
// everything after the closing moves with it; the lift's acceleration sets the lift's length,
// and the hold lasts as long as asked. The default
// closing keeps the script's timeline as written.
void apply_timing(const hand::Skeleton& skeleton, const GraspClosing& closing,
                  PinchScript& script) {
  const GraspClosing standard;
  if (closing.closing_speed == standard.closing_speed && closing.lead_s == standard.lead_s &&
      closing.hold_s == standard.hold_s && closing.lift_acceleration == standard.lift_acceleration)
    return;
  const double closing_s = closing.closing_speed > 0
                               ? (0.015 + closing.over_closure) / closing.closing_speed
                               : script.close_end - script.approach_end;
  const double lag = std::abs(closing.lead_s);
  if (lag > 0) {
    const std::string later = closing.lead_s > 0 ? "index" : "thumb";
    script.dof_delay.assign(skeleton.dofs.size(), 0.0);
    for (std::size_t k = 0; k < skeleton.dofs.size(); ++k)
      if (skeleton.dofs[k].name.rfind(later, 0) == 0) script.dof_delay[k] = lag;
  }
  // A smoothstep lift of height h over T peaks at 6 h / T^2, at its start.
  const double settle = script.lift_start - script.close_end,
               lift = closing.lift_acceleration > 0
                          ? std::sqrt(6 * script.lift_height / closing.lift_acceleration)
                          : script.lift_end - script.lift_start,
               release = script.release_end - script.hold_end,
               fall = script.end - script.release_end;
  script.close_end = script.approach_end + closing_s;
  script.lift_start = script.close_end + lag + settle;
  script.lift_end = script.lift_start + lift;
  script.hold_end = script.lift_end + closing.hold_s;
  script.release_end = script.hold_end + release;
  script.end = script.release_end + fall;
}

}  // namespace

hand::HandPose PinchScript::target(double t) const {
  hand::HandPose pose;
  if (!recorded_poses.empty() && t < close_end) {
    if (t >= approach_end) {  // the recording, from its first pose at approach_end
      const auto after =
          std::upper_bound(recorded_times.begin(), recorded_times.end(), t - approach_end);
      return recorded_poses[std::size_t(
          std::max<std::ptrdiff_t>(0, std::distance(recorded_times.begin(), after) - 1))];
    }
    hand::HandPose flat = open;  // shaped into the first pose as the script's pinch is
    flat.angles.setZero();
    pose = blend(flat, open, smooth(t / shape_end));
    pose.root_position.y() +=
        approach_height * (1 - smooth((t - shape_end) / (approach_end - shape_end)));
    return pose;
  }
  if (t < approach_end) {
    hand::HandPose flat = open;
    flat.angles.setZero();
    pose = blend(flat, open, smooth(t / shape_end));
  } else if (t < hold_end && dof_delay.empty()) {
    pose = blend(open, pinch, smooth((t - approach_end) / (close_end - approach_end)));
  } else if (t < hold_end) {
    pose = open;
    for (Eigen::Index k = 0; k < pose.angles.size(); ++k) {
      const double w =
          smooth((t - approach_end - dof_delay[std::size_t(k)]) / (close_end - approach_end));
      pose.angles(k) = open.angles(k) + w * (pinch.angles(k) - open.angles(k));
    }
  } else {
    pose = blend(pinch, open, smooth((t - hold_end) / (release_end - hold_end)));
  }
  pose.root_rotation = pinch.root_rotation;
  pose.root_position =
      pinch.root_position +
      Eigen::Vector3d(0,
                      approach_height * (1 - smooth((t - shape_end) / (approach_end - shape_end))) +
                          lift_height * smooth((t - lift_start) / (lift_end - lift_start)),
                      0);
  if (jitter) jitter->apply(jitter_start + t, jitter_scale, pose);
  return pose;
}

Eigen::Isometry3d PinchScript::start_root() const {
  const hand::HandPose first = target(0.0);
  Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
  root.linear() = first.root_rotation;
  root.translation() = first.root_position;
  return root;
}

namespace {

// How high above the pinch a hand placed by the pinch's rule shapes from flat into the open
// pose: 5 cm, or as many centimetres more as keep every skin point 1 cm off the cube and out of
// its column (placement_clearance) through the shaping (the rule's steeper hand over the 6 cm cube
// swept its flat fingers through it from 5 cm). A hand the rule leaves alone shapes at 5 cm, as
// before the rule.
double clear_approach_height(const hand::Skeleton& ik, const HandSimModel& model,
                             const PinchScript& script, const RigidPose& cube) {
  constexpr double kLowest = 0.05, kHighest = 0.20, kRaise = 0.01, kClear = 0.01;
  constexpr int kSamples = 5;  // of the shaping, flat to open
  hand::HandPose flat = script.open;
  flat.angles.setZero();
  for (double height = kLowest;; height += kRaise) {
    bool clear = true;
    for (int i = 0; i < kSamples && clear; ++i) {
      hand::HandPose pose = blend(flat, script.open, double(i) / (kSamples - 1));
      pose.root_position.y() += height;
      clear =
          placement_clearance(ik, model, pose, cube, model.cube_half, {-1, -1}).distance >= kClear;
    }
    if (clear || height >= kHighest) return height;
  }
}

// Where `pose` (the pads `wrist_squeeze` inside the faces) lays other skin deeper than
// kPinningDepth inside the cube (a finger across a 6 cm cube's top), the hand is placed again
// by the pinch's rule, the pads on the faces (`on_faces`), the rest of the hand clear of the
// cube, the pads' facing (the points behind them) at a tenth of their weight: the rule asks
// for the pads' places, and a pad turned a few degrees still presses its face
// (pinch_clearance.h), a functional pinch still drawn towards the functional posture.
// Sets the script's pinch and what the placement measured.
void place_by_rule(const hand::Skeleton& ik, const HandSimModel& model,
                   const std::vector<retarget::Feature>& features,
                   const std::vector<Eigen::Vector3d>& on_faces, const RigidPose& cube,
                   const hand::HandPose& pose, PinchScript& script) {
  const std::array<int, 2> pads = {script.thumb_bone, script.index_bone};
  script.pinch = pose;
  script.pinch_clearance =
      placement_clearance(ik, model, pose, cube, model.cube_half, pads).distance;
  if (script.pinch_clearance >= -kPinningDepth) return;
  std::vector<retarget::Feature> relaxed = features;
  relaxed[2].weight = relaxed[3].weight = 0.1;
  const PosturePull pull =
      script.posture == PinchPosture::kFunctional ? functional_pull(ik, pose) : PosturePull{};
  const ClearPinch clear = clear_pinch(ik, model, relaxed, on_faces, cube, pads, pose, pull);
  script.pinch = clear.pose;
  script.pinch_clearance = clear.clearance.distance;
  script.placed_by_rule = true;
  script.pinch_meets_rule = clear.meets_rule();
  script.placement_pad_error = clear.pad_error;
}

// The open pose's nearest skin to the cube or its column (PinchScript::open_clearance).
double open_clearance(const hand::Skeleton& ik, const HandSimModel& model,
                      const hand::HandPose& open, const RigidPose& cube) {
  return placement_clearance(ik, model, open, cube, model.cube_half, {-1, -1}).distance;
}

// A hand placed by the pinch's rule comes down in an open pose whose skin is aimed
// kDescentClearance off the cube and its column: where the open pose comes nearer, every finger's
// joints are placed again (pinch_clearance.h; the curled fingers' too, which then move as the hand
// closes), the pads aiming at `open_goals` with their facing at a tenth of its weight, as the rule
// places the pinch.
void clear_the_descent(const hand::Skeleton& ik, const HandSimModel& model,
                       const std::vector<retarget::Feature>& features,
                       const std::vector<Eigen::Vector3d>& open_goals, const RigidPose& cube,
                       PinchScript& script) {
  if (script.open_clearance >= kDescentClearance) return;
  std::vector<retarget::Feature> relaxed = features;
  relaxed[2].weight = relaxed[3].weight = 0.1;
  script.open = clear_descent(ik, model, relaxed, open_goals, cube, script.open);
  script.open_clearance = open_clearance(ik, model, script.open, cube);
}

// The farther of the two pads (the first two features) from its goal at `pose`.
double pads_miss(const hand::Skeleton& ik, const std::vector<retarget::Feature>& features,
                 const hand::HandPose& pose, const std::vector<Eigen::Vector3d>& goals) {
  const hand::BoneFrames frames = hand::forward_kinematics(ik, pose);
  double miss = 0.0;
  for (std::size_t pad = 0; pad < 2; ++pad)
    miss = std::max(miss,
                    (hand::marker_position(ik, frames, features[pad].marker) - goals[pad]).norm());
  return miss;
}

// The hand placed, wrist and fingers, where the pads reach `goals` (the features' order), in
// `posture` (pinch_posture.h).
hand::HandPose placed_pose(const hand::Skeleton& ik, const std::vector<retarget::Feature>& features,
                           const std::vector<Eigen::Vector3d>& goals, hand::HandPose pose,
                           PinchPosture posture, const retarget::SolverOptions& options) {
  if (posture == PinchPosture::kFunctional)
    return place_in_posture(ik, features, goals, pose, functional_pull(ik, pose), true);
  const retarget::SolverResult placed =
      retarget::FingertipSolver(ik, features, options).solve(pose, goals, true);
  pose.angles = placed.angles;
  pose.root_position += placed.root_shift;
  return pose;
}

// From script.pinch as placed, the fingers alone: closed on to `closed` (where `close`) and
// opened to `open` (the pads 15 mm off the faces), in script.posture.
void close_and_open(const hand::Skeleton& ik, const std::vector<retarget::Feature>& features,
                    const std::vector<Eigen::Vector3d>& closed,
                    const std::vector<Eigen::Vector3d>& open, bool close,
                    const retarget::SolverOptions& options, PinchScript& script) {
  if (script.posture == PinchPosture::kFunctional) {
    const hand::HandPose placed = script.pinch;
    // Drawn towards the placed pinch's own angles: the hand closes from the posture it took.
    const PosturePull pull{placed.angles, posture_dofs(ik), functional_posture().weight};
    if (close) script.pinch = place_in_posture(ik, features, closed, placed, pull, false);
    // Opened as a hand opens, the pads no longer held face to face, from the pinch as placed:
    // the hand opens the same however far it will close past the faces.
    std::vector<retarget::Feature> loose = features;
    loose[2].weight = loose[3].weight = 0.1;
    script.open = place_in_posture(ik, loose, open, placed, pull, false);
    return;
  }
  if (close)
    script.pinch.angles =
        retarget::FingertipSolver(ik, features, options).solve(script.pinch, closed, true).angles;
  const retarget::SolverResult opened =
      retarget::FingertipSolver(ik, features, options).solve(script.pinch, open, true);
  script.open = script.pinch;
  script.open.angles = opened.angles;
}

// The script of `closing`: the hand placed where the pads reach `wrist_squeeze` inside the faces,
// or on them where the pinch's rule places it again (place_by_rule); a closing past that goes
// on with the fingers alone.
PinchScript make_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                        const GraspClosing& closing, double wrist_squeeze, PinchPosture posture) {
  const double squeeze = closing.over_closure;
  PinchScript script;
  script.cube_size = 2 * model.cube_half.x();
  script.squeeze = squeeze;
  script.posture = posture;
  script.scripted_placement =
      same_placement(closing, GraspClosing{}) && wrist_squeeze == GraspClosing{}.over_closure;
  script.cube_centre = Eigen::Vector3d(0, script.cube_size / 2, 0);
  const PinchPads pads = pinch_pads(skeleton, model);
  script.thumb_bone = pads.thumb_bone;
  script.index_bone = pads.index_bone;
  // Pads as markers: on the palmar side of the distal bones' middles, and 12 mm further in,
  // so that aiming both at the cube's axis turns the pads to face each other.
  hand::Skeleton ik = skeleton;
  const int first = int(ik.markers.size());
  for (const auto& [bone, pad] :
       {std::pair{pads.thumb_bone, pads.thumb_pad}, std::pair{pads.index_bone, pads.index_pad}}) {
    ik.markers.push_back({"pad", bone, pad});
    ik.markers.push_back({"pad_in", bone, pad - Eigen::Vector3d(0, 0, 0.012)});
  }
  const std::vector<retarget::Feature> features = {
      {first, -1, 1.0}, {first + 2, -1, 1.0}, {first + 1, -1, 0.3}, {first + 3, -1, 0.3}};
  // Palm down, fingers along the floor, rolled 60 degrees towards the thumb so that thumb and
  // index can oppose across the cube.
  Eigen::Matrix3d palm_down;
  palm_down.col(0) = Eigen::Vector3d(0, 0, -1);
  palm_down.col(1) = Eigen::Vector3d(1, 0, 0);
  palm_down.col(2) = Eigen::Vector3d(0, -1, 0);
  hand::HandPose pose = hand::HandPose::rest(ik);
  // Middle, ring and pinky curled out of the way, as people pinch.
  for (std::size_t k = 0; k < ik.dofs.size(); ++k) {
    const hand::Dof& dof = ik.dofs[k];
    const bool other = dof.name.rfind("middle", 0) == 0 || dof.name.rfind("ring", 0) == 0 ||
                       dof.name.rfind("pinky", 0) == 0;
    if (other && dof.name.find("flexion") != std::string::npos)
      pose.angles(Eigen::Index(k)) = 0.7 * dof.upper;
  }
  pose.root_rotation =
      Eigen::AngleAxisd(-M_PI / 3, Eigen::Vector3d::UnitX()).toRotationMatrix() * palm_down;
  hand::BoneFrames frames = hand::forward_kinematics(ik, pose);
  Eigen::Vector3d thumb = hand::marker_position(ik, frames, first),
                  index = hand::marker_position(ik, frames, first + 2);
  // The faces the pads go to: across the cube along z, the thumb on its own side. The
  // closing's tilt turns that axis about the vertical (yaw) and the faces' horizontal (pitch),
  // and the hand with it: a person pinching askew turns the hand, the pads still opposed.
  Eigen::Vector3d axis(0, 0, (thumb - index).z() > 0 ? 1.0 : -1.0);
  Eigen::Vector3d above(0, 0.01, 0);  // the wrist's first guess: above the pads' midpoint
  if (closing.tilt_yaw != 0.0 || closing.tilt_pitch != 0.0) {
    const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(closing.tilt_yaw, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(closing.tilt_pitch, Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    axis = tilt * axis;
    above = tilt * above;
    pose.root_rotation = tilt * pose.root_rotation;
    frames = hand::forward_kinematics(ik, pose);
    thumb = hand::marker_position(ik, frames, first);
    index = hand::marker_position(ik, frames, first + 2);
  }
  // Where the pads take the faces: 20 mm under the top, so that the distal phalanges (about
  // 2 cm) lie on the faces rather than over the top edge (at 12 mm the fingertips hooked over
  // it, and once the skin no longer let the edge sink in between its nodes the heavy cube
  // turned out of the pads at the lift for 4 of 15 squeezes), but not above 0.4 of the side,
  // so that a finger that touches first slides a light cube instead of tipping it (pushed at
  // height z, a cube on a floor of friction mu tips before it slides when z > side / (2 mu)).
  const double pad_height = std::max(0.4 * script.cube_size, script.cube_size - 0.020);
  const Eigen::Vector3d centre(script.cube_centre.x() + closing.offset_along * script.cube_size,
                               pad_height, script.cube_centre.z());
  pose.root_position = centre + above - 0.5 * (thumb + index);
  auto goals = [&](double gap) {
    const double half = script.cube_size / 2 + gap;
    // In the features' order: the pads, then the points behind them.
    return std::vector<Eigen::Vector3d>{centre + axis * half, centre - axis * half,
                                        centre + axis * (half + 0.012),
                                        centre - axis * (half + 0.012)};
  };
  retarget::SolverOptions options;
  options.root_translation_weight = 1e-3;  // the wrist may move to where both pads reach
  options.max_iterations = options.cold_start_iterations = 200;
  // Solved to convergence once: undamped, whose last steps converge fastest.
  options.relative_decrease_tolerance = options.residual_damping = 0.0;
  pose = placed_pose(ik, features, goals(-wrist_squeeze), pose, posture, options);
  RigidPose cube;
  cube.position = script.cube_centre;
  place_by_rule(ik, model, features, goals(0.0), cube, pose, script);
  options.root_translation_weight = 0.0;  // from here on the same wrist
  close_and_open(ik, features, goals(-squeeze), goals(0.015),
                 script.placed_by_rule || squeeze != wrist_squeeze, options, script);
  script.pinch_error = pads_miss(ik, features, script.pinch, goals(-squeeze));
  script.open_clearance = open_clearance(ik, model, script.open, cube);
  if (script.placed_by_rule) {
    clear_the_descent(ik, model, features, goals(0.015), cube, script);
    script.approach_height = clear_approach_height(ik, model, script, cube);
  }
  return script;
}

}  // namespace

PinchScript make_pinch_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                              double squeeze, PinchPosture posture) {
  GraspClosing closing;
  closing.over_closure = squeeze;
  return make_script(skeleton, model, closing, squeeze, posture);
}

// The closing's fields make_script reads: the rest only time the script (apply_timing), lay
// the jitter on or move the cube.
bool same_placement(const GraspClosing& a, const GraspClosing& b) {
  return a.over_closure == b.over_closure && a.tilt_yaw == b.tilt_yaw &&
         a.tilt_pitch == b.tilt_pitch && a.offset_along == b.offset_along;
}

// The wrist goes where the script's pinch puts it; a closing past (or short of) that goes on
// with the fingers alone, as a person's fingers close on past a face they do not feel.
PinchScript place_grasp(const hand::Skeleton& skeleton, const HandSimModel& model,
                        const GraspClosing& closing, PinchPosture posture) {
  return make_script(skeleton, model, closing, GraspClosing{}.over_closure, posture);
}

PinchScript time_grasp(PinchScript placed, const hand::Skeleton& skeleton,
                       const GraspClosing& closing, std::shared_ptr<const PoseJitter> jitter) {
  PinchScript script = std::move(placed);
  script.scripted_placement = false;  // timed
  apply_timing(skeleton, closing, script);
  if (closing.jitter > 0) {
    if (!jitter) throw std::invalid_argument("a closing with jitter needs a recording's jitter");
    script.jitter_start = closing.jitter_phase * jitter->duration();
    script.jitter = std::move(jitter);
    script.jitter_scale = closing.jitter;
  }
  // The cube where it lies, the hand aimed where it was to lie.
  script.cube_centre.x() += closing.cube_shift_x;
  script.cube_centre.z() += closing.cube_shift_z;
  return script;
}

PinchScript make_grasp_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                              const GraspClosing& closing, std::shared_ptr<const PoseJitter> jitter,
                              PinchPosture posture) {
  return time_grasp(place_grasp(skeleton, model, closing, posture), skeleton, closing,
                    std::move(jitter));
}

double cube_turn_deg(const HandSimState& state) {
  return state.cube_pose.rotation.angularDistance(Eigen::Quaterniond::Identity()) * 180 / M_PI;
}

double grip_force(const HandSimModel& model, const HandSimState& state) {
  const std::array<double, 6> faces = flesh_forces_on_cube_faces(model, state);
  double grip = 0.0;
  for (std::size_t axis = 0; axis < 3; ++axis)
    grip = std::max(grip, std::min(faces[2 * axis], faces[2 * axis + 1]));
  return grip;
}

PinchMeter::PinchMeter(const HandSimModel& model, const PinchScript& script)
    : model_(model), script_(script) {}

void PinchMeter::observe(const HandSimState& state, double t, double max_penetration) {
  inverted_tets_ = std::max(inverted_tets_, inverted_tet_count(model_, state));
  if (t <= script_.approach_end + 1e-9)
    top_load_before_closing_n_ =
        std::max(top_load_before_closing_n_, flesh_forces_on_cube_faces(model_, state)[3]);
  if (t < script_.lift_end - 1e-9 || t > script_.hold_end + 1e-9) return;
  // The hold: the cube seen from the distal bones, relative to the midpoint of their origins.
  const hand::BoneFrames frames = simulated_bone_frames(model_, state);
  const std::size_t ti = std::size_t(script_.thumb_bone), ii = std::size_t(script_.index_bone);
  const Eigen::Vector3d between =
      frames.rotation[ii].transpose() *
      (state.cube_pose.position - 0.5 * (frames.origin[ti] + frames.origin[ii]));
  if (!reference_set_) {
    reference_ = between;
    reference_set_ = true;
  }
  slip_mm_ = std::max(slip_mm_, 1000 * (between - reference_).norm());
  max_penetration_mm_ = std::max(max_penetration_mm_, 1000 * max_penetration);
  peak_grip_n_ = std::max(peak_grip_n_, grip_force(model_, state));
  turn_deg_ = cube_turn_deg(state);
  lift_ = state.cube_pose.position.y() - script_.cube_centre.y();
  // Half the lift: a cube that fell is back on the floor, while one held but turned in the
  // grip hangs up to about a side's third lower than the pads (at 80 % a 6 cm cube held at
  // 12 N with 0.02 mm of slip, turned 15 degrees, counted as lost).
  holding_ = holding_ && lift_ >= 0.5 * script_.lift_height;
}

void PinchMeter::finish(const HandSimState& state, double duration, bool flesh_on_cube,
                        PinchReport& report) const {
  report.held = reference_set_ && holding_;
  report.lift = lift_;
  report.slip_mm = slip_mm_;
  report.max_penetration_mm = max_penetration_mm_;
  report.peak_grip_n = peak_grip_n_;
  report.turn_deg = turn_deg_;
  report.top_load_before_closing_n = top_load_before_closing_n_;
  report.inverted_tets = inverted_tets_;
  // Released: no flesh on the cube and the cube back down, a corner within 1 mm of the floor
  // (dropped from the lift's height it may still be tumbling, as a real one does).
  double lowest = INFINITY;
  const Eigen::Vector3d up = model_.parameters.floor_normal.normalized();
  for (int k = 0; k < 8; ++k)
    lowest = std::min(
        lowest, up.dot(cube_corner(model_, state.cube_pose, k)) - model_.parameters.floor_height);
  report.released = duration >= script_.end && lowest < 0.001 && !flesh_on_cube;
}

int pinch_step_count(double duration, double time_step) {
  return int(std::ceil(duration / time_step - 1e-9));
}

PinchReport run_pinch(const HandSimModel& model, const hand::Skeleton& skeleton,
                      const PinchScript& script, const SimOptions& options, double duration,
                      const std::function<void(const HandSimState&)>& observer) {
  if (duration <= 0) duration = script.end;
  RigidPose cube;
  cube.position = script.cube_centre;
  HandSimState state = initial_state(model, skeleton, script.start_root(), cube);
  HandSimulator simulator(model, options);
  const double h = model.parameters.time_step;
  const int steps = pinch_step_count(duration, h);
  PinchReport report;
  PinchMeter meter(model, script);
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 1) * h;  // the time the step reaches
    const std::vector<RigidPose> targets = bone_targets(model, skeleton, script.target(t));
    const auto begin = std::chrono::steady_clock::now();
    const SimStepReport step = simulator.step(state, targets);
    report.step_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
            .count());
    report.newton_iterations.push_back(step.newton_iterations);
    report.linear_iterations.push_back(step.linear_iterations);
    report.factorizations.push_back(step.factorizations);
    report.contacts.push_back(step.contacts);
    report.halvings.push_back(step.halvings);
    report.direct_solves.push_back(step.direct_solves);
    report.failed_cg.push_back(step.failed_cg);
    report.timer_ms.push_back(step.timer_ms);
    if (observer) observer(state);
    meter.observe(state, t, step.max_penetration);
  }
  meter.finish(state, duration, !state.node_cube.empty() || !state.sample_cube.empty(), report);
  return report;
}

}  // namespace handlab::sim
