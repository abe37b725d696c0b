#include "studies/session/scripted_tracker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/hand/tracked_hand.h"
#include "core/retarget/fingertip_solver.h"
#include "core/tracking/hand_fitting.h"
#include "studies/session/tracker.h"

namespace handlab::studies {
namespace {

// Palm down (palmar +z to -y), fingers forward (distal +y to -z), radial +x to -x.
Eigen::Matrix3d palm_down() {
  Eigen::Matrix3d r;
  r.col(0) = -Eigen::Vector3d::UnitX();
  r.col(1) = -Eigen::Vector3d::UnitZ();
  r.col(2) = -Eigen::Vector3d::UnitY();
  return r;
}

double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// The tracked hand with thumb and index tips `gap` apart (m), other fingers curled.
hand::HandPose pinch_pose(const hand::Skeleton& s, const Eigen::Matrix3d& rotation, double gap) {
  hand::HandPose pose = hand::HandPose::rest(s);
  pose.root_rotation = rotation;
  for (const char* f : {"index", "middle", "ring", "pinky"}) {
    const bool index = std::string(f) == "index";
    pose.angles(s.dof_index(std::string(f) + "_mcp_flexion")) = index ? 0.5 : 0.9;
    pose.angles(s.dof_index(std::string(f) + "_pip_flexion")) = index ? 0.6 : 1.2;
    pose.angles(s.dof_index(std::string(f) + "_dip_flexion")) = index ? 0.3 : 0.6;
  }
  const int thumb = s.marker_index("thumb_tip"), index = s.marker_index("index_tip");
  const hand::BoneFrames start = hand::forward_kinematics(s, pose);
  const Eigen::Vector3d direction =
      (hand::marker_position(s, start, thumb) - hand::marker_position(s, start, index))
          .normalized();
  retarget::SolverOptions options;
  options.spatial_weight = options.temporal_weight = 1e-9;
  options.max_iterations = options.cold_start_iterations = 60;
  // Solved to convergence once: undamped, whose last steps converge fastest.
  options.decrease_tolerance = options.relative_decrease_tolerance = options.residual_damping = 0.0;
  retarget::FingertipSolver solver(s, {{thumb, index, 1.0}}, options);
  pose.angles = solver.solve(pose, {gap * direction}).angles;
  return pose;
}

tracking::TrackedFrame frame_of(const hand::Skeleton& s, const hand::HandPose& pose, double time,
                                long id) {
  tracking::TrackedFrame f;
  f.timestamp = time;
  f.id = id;
  tracking::TrackedHand h =
      tracking::tracked_hand(hand::to_leap_joints(s, pose), tracking::Side::kRight);
  f.hands.push_back(h);
  return f;
}

// Root position that puts the scaled thumb-index midpoint (scaled about the palm centre, as
// the retargeter does) on `target`.
Eigen::Vector3d root_for_pinch_at(const hand::Skeleton& s, hand::HandPose pose, double scale,
                                  const Eigen::Vector3d& target) {
  pose.root_position.setZero();
  const hand::LeapJoints j = hand::to_leap_joints(s, pose);
  const Eigen::Vector3d middle = 0.5 * (j.joints[0][4] + j.joints[1][4]);
  return target - j.palm_position - scale * (middle - j.palm_position);
}

}  // namespace

std::vector<tracking::TrackedFrame> scripted_open_palm(const ScriptedMotionSettings& settings) {
  const hand::Skeleton s =
      hand::build_tracked_hand(hand::HandShape::with_length(settings.hand_length));
  hand::HandPose open = hand::HandPose::rest(s);
  open.root_rotation = palm_down();
  open.root_position = settings.layout.zone_a + Eigen::Vector3d(0, 0.20, 0.05);
  std::vector<tracking::TrackedFrame> frames;
  for (long k = 0; k < long(settings.rate_hz); ++k)
    frames.push_back(frame_of(s, open, double(k) / settings.rate_hz, k));
  return frames;
}

retarget::Calibration scripted_calibration(const task::SceneLayout& scene, double hand_length,
                                           const hand::Skeleton& first_hand,
                                           SessionControl* control) {
  ScriptedMotionSettings settings;
  settings.hand_length = hand_length;
  settings.layout = scene;
  const std::vector<tracking::TrackedFrame> open = scripted_open_palm(settings);
  const auto calibration = retarget::calibrate_open_palm(
      open, tracking::Side::kRight, first_hand,
      tracking::TrackedHandFitter(hand_length, tracking::Side::kRight));
  if (!calibration) throw std::runtime_error("the scripted open palm did not calibrate");
  report_calibration(control, *calibration, open.back());
  return *calibration;
}

ScriptedTracker::ScriptedTracker(const ScriptedMotionSettings& settings)
    : settings_(settings),
      skeleton_(hand::build_tracked_hand(hand::HandShape::with_length(settings.hand_length))),
      root_rotation_(palm_down()) {
  const double cube = settings.layout.cube_size;
  const double s = settings.scale;
  // Tip centres a radius closer than the cube's faces in the simulated hand: a firm pinch.
  const double gap = (cube + settings.simulated_tip_radius) / s;
  const hand::HandPose pinch = pinch_pose(skeleton_, root_rotation_, gap);
  const hand::HandPose wide = pinch_pose(skeleton_, root_rotation_, gap + 0.04 / s);
  Eigen::VectorXd open = hand::HandPose::rest(skeleton_).angles;

  const Eigen::Vector3d at_a = settings.layout.zone_a + Eigen::Vector3d(0, 0.5 * cube, 0);
  const Eigen::Vector3d at_b = settings.layout.zone_b + Eigen::Vector3d(0, 0.5 * cube + 0.001, 0);
  const Eigen::Vector3d up(0, 0.10, 0);
  const Eigen::Vector3d grasp = root_for_pinch_at(skeleton_, pinch, s, at_a);
  const Eigen::Vector3d place = root_for_pinch_at(skeleton_, pinch, s, at_b);
  keys_ = {
      {0.0, grasp + up, open},         {0.8, grasp + Eigen::Vector3d(0, 0.02, 0), wide.angles},
      {1.2, grasp, wide.angles},       {1.7, grasp, pinch.angles},
      {1.9, grasp, pinch.angles},      {2.7, grasp + up, pinch.angles},
      {3.9, place + up, pinch.angles}, {4.7, place, pinch.angles},
      {4.9, place, pinch.angles},      {5.3, place, wide.angles},
      {6.1, place + up, open},
  };
  for (Key& key : keys_) key.time *= settings.tempo;
}

double ScriptedTracker::duration() const {
  return keys_.back().time;
}

std::optional<tracking::TrackedFrame> ScriptedTracker::next() {
  const double t = double(frame_) / settings_.rate_hz;
  if (t > duration()) return std::nullopt;
  std::size_t k = 0;
  while (k + 2 < keys_.size() && keys_[k + 1].time <= t) ++k;
  const Key& a = keys_[k];
  const Key& b = keys_[k + 1];
  const double u = smoothstep((t - a.time) / (b.time - a.time));
  hand::HandPose pose = hand::HandPose::rest(skeleton_);
  pose.root_rotation = root_rotation_;
  pose.root_position = (1 - u) * a.root_position + u * b.root_position;
  pose.angles = (1 - u) * a.angles + u * b.angles;
  return frame_of(skeleton_, pose, t, frame_++);
}

}  // namespace handlab::studies
