#include "studies/analysis/logged_closing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/sim/box_distance.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/cube_task.h"
#include "core/task/pinch_clearance.h"

namespace handlab::studies {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + std::ptrdiff_t(mid)));
}

bool grasped(const store::FrameRecord& f) {
  return task::TaskPhase(f.task_phase) == task::TaskPhase::kGrasped;
}

// The time a digit's touch began in the run of frames touching the cube that reaches `grasp`.
double touch_began(const std::vector<store::FrameRecord>& frames, std::size_t grasp,
                   bool store::FrameRecord::*touching) {
  if (!(frames[grasp].*touching)) return std::numeric_limits<double>::quiet_NaN();
  std::size_t k = grasp;
  while (k > 0 && frames[k - 1].*touching) --k;
  return frames[k].time;
}

double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * double(sorted.size() - 1);
  const std::size_t low = std::size_t(std::floor(at));
  const std::size_t high = std::min(low + 1, sorted.size() - 1);
  return sorted[low] + (at - double(low)) * (sorted[high] - sorted[low]);
}

}  // namespace

const std::vector<LoggedFactor>& logged_factors() {
  static const std::vector<LoggedFactor> factors = {
      {"over_closure", "mm", &LoggedClosing::over_closure, 1e-3},
      {"tilt_yaw", "deg", &LoggedClosing::tilt_yaw, M_PI / 180},
      {"tilt_pitch", "deg", &LoggedClosing::tilt_pitch, M_PI / 180},
      {"offset_along", "side", &LoggedClosing::offset_along, 1.0},
      {"lead", "ms", &LoggedClosing::lead_s, 1e-3},
      {"closing_speed", "cm/s", &LoggedClosing::closing_speed, 1e-2},
      {"other_skin_depth", "mm", &LoggedClosing::other_skin_depth, 1e-3},
  };
  return factors;
}

FactorSpread factor_spread(const std::vector<LoggedClosing>& closings, const LoggedFactor& f) {
  std::vector<double> values;
  for (const LoggedClosing& c : closings) values.push_back(c.*(f.field));
  return spread_of(values, f.scale);
}

FactorSpread spread_of(const std::vector<double>& values, double unit) {
  std::vector<double> kept;
  for (double v : values)
    if (!std::isnan(v)) kept.push_back(v / unit);
  FactorSpread s;
  s.n = int(kept.size());
  if (kept.empty()) return s;
  std::sort(kept.begin(), kept.end());
  s.p10 = quantile(kept, 0.1);
  s.median = quantile(kept, 0.5);
  s.p90 = quantile(kept, 0.9);
  return s;
}

ClosingReader::ClosingReader(const hand::HandShape& simulated_hand)
    : skeleton_(hand::build_simulated_hand(simulated_hand)) {
  const hand::HandFlesh flesh = hand::build_flesh(skeleton_, simulated_hand);
  model_ = sim::make_hand_sim_model(skeleton_, flesh, {});
  pads_ = sim::pinch_pads(skeleton_, model_);
}

double ClosingReader::other_skin_depth(const store::FrameRecord& f, double side) const {
  sim::RigidPose cube;
  cube.position = f.cube_position.cast<double>();
  cube.rotation = f.cube_rotation.cast<double>();
  return -sim::skin_clearance(skeleton_, model_, pose_at(f), cube,
                              Eigen::Vector3d::Constant(side / 2),
                              {pads_.thumb_bone, pads_.index_bone})
              .distance;
}

hand::HandPose ClosingReader::pose_at(const store::FrameRecord& f) const {
  hand::HandPose pose;
  pose.root_position = f.root_position.cast<double>();
  pose.root_rotation = f.root_rotation.cast<double>().toRotationMatrix();
  pose.angles = Eigen::Map<const Eigen::VectorXf>(f.angles.data(), Eigen::Index(f.angles.size()))
                    .cast<double>();
  if (pose.angles.size() != Eigen::Index(skeleton_.dofs.size()))
    throw std::runtime_error("a frame's intermediate hand has " +
                             std::to_string(pose.angles.size()) + " angles, the hand " +
                             std::to_string(skeleton_.dofs.size()));
  return pose;
}

ClosingReader::Pads ClosingReader::pads_at(const store::FrameRecord& f) const {
  const sim::PadPoints world =
      sim::pad_points(hand::forward_kinematics(skeleton_, pose_at(f)), pads_);
  const Eigen::Quaterniond cube = f.cube_rotation.cast<double>();
  const Eigen::Vector3d centre = f.cube_position.cast<double>();
  auto in_cube = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return cube.conjugate() * (p - centre);
  };
  return {in_cube(world.thumb), in_cube(world.index)};
}

LoggedClosing ClosingReader::read(const std::vector<store::FrameRecord>& frames, std::size_t grasp,
                                  double side) const {
  LoggedClosing c;
  const double thumb_touch = touch_began(frames, grasp, &store::FrameRecord::thumb_contact),
               index_touch = touch_began(frames, grasp, &store::FrameRecord::index_contact);
  c.lead_s = index_touch - thumb_touch;
  // The frame before either digit touched (the pads still on their own sides) sets the faces'
  // axis; the frame both touched from, the closing's tilt and offset.
  // The frame at `time` (with `before`, the one before it), or a later one that holds the hand:
  // a trial's first frames may come before the tracker saw it.
  auto frame_at = [&](double time, int before) {
    std::size_t k = grasp;
    while (k > 0 && frames[k].time > time) --k;
    if (before && k > 0 && frames[k].time >= time) --k;
    while (k < grasp && frames[k].angles.size() != skeleton_.dofs.size()) ++k;
    return k;
  };
  const double first = std::fmin(thumb_touch, index_touch),
               both = std::fmax(thumb_touch, index_touch);
  const std::size_t apart = std::isnan(first) ? grasp : frame_at(first, 1);
  const bool both_seen = !std::isnan(thumb_touch) && !std::isnan(index_touch);
  const std::size_t touching = both_seen ? frame_at(both, 0) : grasp;
  const Pads before = pads_at(frames[apart]);
  Eigen::Index n = 0;
  (before.thumb - before.index).cwiseAbs().maxCoeff(&n);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  normal(n) = (before.thumb - before.index)(n) > 0 ? 1.0 : -1.0;
  // Each pad past its face: half of what the gap between them falls short of the side.
  std::vector<double> depths, other_depths;
  for (std::size_t k = grasp; k < frames.size() && grasped(frames[k]); ++k) {
    const Pads p = pads_at(frames[k]);
    depths.push_back(0.5 * (side - (p.thumb - p.index).dot(normal)));
    other_depths.push_back(other_skin_depth(frames[k], side));
  }
  c.over_closure = median(depths);
  c.other_skin_depth = median(other_depths);
  const store::FrameRecord& f = frames[touching];
  const Pads p = pads_at(f);
  const Eigen::Vector3d axis = (p.thumb - p.index).normalized();
  const Eigen::Vector3d up_in_cube =
      f.cube_rotation.cast<double>().conjugate() * Eigen::Vector3d::UnitY();
  Eigen::Index u = (n + 1) % 3, h = (n + 2) % 3;
  if (std::abs(up_in_cube(h)) > std::abs(up_in_cube(u))) std::swap(u, h);
  const double along_n = std::abs(axis(n));
  c.tilt_yaw = std::atan2(std::abs(axis(h)), along_n);
  c.tilt_pitch = std::atan2(std::abs(axis(u)), along_n);
  c.offset_along = std::abs(0.5 * (p.thumb + p.index)(h)) / side;
  // Each pad's mean speed against the cube over the 0.1 s before its touch began (a frame's
  // step alone would be the tracker's jitter more than the closing).
  std::vector<double> speeds;
  for (const auto& [touch, thumb] : {std::pair{thumb_touch, true}, std::pair{index_touch, false}}) {
    if (std::isnan(touch)) continue;
    const std::size_t k = frame_at(touch, 0), from = frame_at(touch - 0.1, 0);
    const double dt = frames[k].time - frames[from].time;
    if (dt <= 0) continue;
    const Pads now = pads_at(frames[k]), earlier = pads_at(frames[from]);
    speeds.push_back(
        ((thumb ? now.thumb : now.index) - (thumb ? earlier.thumb : earlier.index)).norm() / dt);
  }
  c.closing_speed = speeds.empty()
                        ? std::numeric_limits<double>::quiet_NaN()
                        : (speeds.size() == 1 ? speeds[0] : 0.5 * (speeds[0] + speeds[1]));
  return c;
}

}  // namespace handlab::studies
