#include "core/task/recorded_pinches.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/task/finger_pads.h"
#include "core/task/pinch_clearance.h"

namespace handlab::sim {
namespace {

constexpr double kClosingDepth = 0.01;  // m: a closing's fall and the rise after it
constexpr double kLeadIn = 0.5;         // s of the recording before the moment

PadPoints pads_at(const hand::Skeleton& skeleton, const hand::HandPose& pose,
                  const PinchPads& pads) {
  return pad_points(hand::forward_kinematics(skeleton, pose), pads);
}

}  // namespace

std::vector<double> pad_apertures(const hand::Skeleton& skeleton, const HandSimModel& model,
                                  const std::vector<hand::HandPose>& poses) {
  const PinchPads pads = pinch_pads(skeleton, model);
  std::vector<double> apertures;
  apertures.reserve(poses.size());
  for (const hand::HandPose& pose : poses) {
    const PadPoints p = pads_at(skeleton, pose, pads);
    apertures.push_back((p.thumb - p.index).norm());
  }
  return apertures;
}

std::vector<RecordedClosing> find_recorded_closings(const hand::Skeleton& skeleton,
                                                    const HandSimModel& model,
                                                    const std::vector<double>& times,
                                                    const std::vector<hand::HandPose>& poses) {
  if (times.size() != poses.size())
    throw std::invalid_argument("find_recorded_closings: times and poses differ in number");
  const std::vector<double> apertures = pad_apertures(skeleton, model, poses);
  const double cube_size = 2 * model.cube_half.x();
  const PinchPads pads = pinch_pads(skeleton, model);
  std::vector<RecordedClosing> closings;
  const int n = int(apertures.size());
  auto emit = [&](int widest, int narrowest) {
    const double hi = apertures[std::size_t(widest)], lo = apertures[std::size_t(narrowest)];
    RecordedClosing c;
    c.takes_cube = hi >= cube_size && lo < cube_size;
    c.moment_frame = widest;
    for (int k = widest; k < narrowest; ++k)
      if (apertures[std::size_t(k)] >= cube_size) c.moment_frame = k;
    c.closed_frame = narrowest;
    c.moment = times[std::size_t(c.moment_frame)];
    c.closed = times[std::size_t(narrowest)];
    c.widest = hi;
    c.narrowest = lo;
    const int a = std::max(0, c.moment_frame - 1), b = std::min(n - 1, c.moment_frame + 1);
    if (times[std::size_t(b)] > times[std::size_t(a)])
      c.closing_speed = 0.5 * (apertures[std::size_t(a)] - apertures[std::size_t(b)]) /
                        (times[std::size_t(b)] - times[std::size_t(a)]);
    const PadPoints at = pads_at(skeleton, poses[std::size_t(c.moment_frame)], pads);
    const Eigen::Vector3d between = at.thumb - at.index;
    c.tilt = std::asin(std::abs(between.y()) / between.norm());
    c.first_frame = c.moment_frame;
    while (c.first_frame > 0 && times[std::size_t(c.first_frame - 1)] >= c.moment - kLeadIn)
      --c.first_frame;
    closings.push_back(c);
  };
  bool falling = false;
  int widest = 0, narrowest = 0;
  for (int k = 0; k < n; ++k) {
    const double a = apertures[std::size_t(k)];
    if (!falling) {
      if (a > apertures[std::size_t(widest)]) widest = k;
      if (a <= apertures[std::size_t(widest)] - kClosingDepth) falling = true, narrowest = k;
    } else {
      if (a < apertures[std::size_t(narrowest)]) narrowest = k;
      if (a >= apertures[std::size_t(narrowest)] + kClosingDepth) {
        emit(widest, narrowest);
        falling = false;
        widest = k;
      }
    }
  }
  if (falling) emit(widest, narrowest);
  return closings;
}

PinchScript make_recorded_pinch_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                                       const std::vector<double>& times,
                                       const std::vector<hand::HandPose>& poses,
                                       const RecordedClosing& closing) {
  if (!closing.takes_cube)
    throw std::invalid_argument(
        "make_recorded_pinch_script: a closing that does not take the cube");
  if (closing.first_frame < 0 || closing.closed_frame >= int(poses.size()) ||
      closing.first_frame > closing.moment_frame || closing.moment_frame > closing.closed_frame)
    throw std::invalid_argument("make_recorded_pinch_script: a closing outside the recording");
  PinchScript script;
  script.cube_size = 2 * model.cube_half.x();
  script.cube_centre = Eigen::Vector3d(0, script.cube_size / 2, 0);
  const PinchPads pads = pinch_pads(skeleton, model);
  script.thumb_bone = pads.thumb_bone;
  script.index_bone = pads.index_bone;
  const PadPoints at = pads_at(skeleton, poses[std::size_t(closing.moment_frame)], pads);
  // Turned (the least turn) so that the pads' line is the cube's z axis, the thumb towards +z,
  // and moved so that their midpoint is the cube's centre.
  const Eigen::Vector3d between = at.thumb - at.index, middle = 0.5 * (at.thumb + at.index);
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(between, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int k = closing.first_frame; k <= closing.closed_frame; ++k) {
    hand::HandPose pose = poses[std::size_t(k)];
    pose.root_position = turn * (pose.root_position - middle) + script.cube_centre;
    pose.root_rotation = turn * pose.root_rotation;
    script.recorded_times.push_back(times[std::size_t(k)] -
                                    times[std::size_t(closing.first_frame)]);
    script.recorded_poses.push_back(std::move(pose));
  }
  script.open = script.recorded_poses.front();
  script.pinch = script.recorded_poses.back();
  // The other skin at the least aperture (pinch_clearance.h), to set beside the map's pinch.
  RigidPose cube;
  cube.position = script.cube_centre;
  script.pinch_clearance = skin_clearance(skeleton, model, script.pinch, cube, model.cube_half,
                                          {script.thumb_bone, script.index_bone})
                               .distance;
  // The script's timeline around the recording: shape and come down, play it, settle, lift
  // 10 cm in a second, hold 2 s, open, let the cube fall.
  script.shape_end = 0.3;
  script.approach_end = 0.8;
  script.close_end =
      script.approach_end + std::max(script.recorded_times.back(), model.parameters.time_step);
  script.lift_start = script.close_end + 0.2;
  script.lift_end = script.lift_start + 1.0;
  script.hold_end = script.lift_end + 2.0;
  script.release_end = script.hold_end + 0.4;
  script.end = script.release_end + 0.8;
  return script;
}

RecordedPinchRun run_recorded_pinch(const HandSimModel& model, const hand::Skeleton& skeleton,
                                    const PinchScript& script, const SimOptions& options) {
  RecordedPinchRun run;
  PinchLossWatch watch(model, script);
  run.report = run_pinch(model, skeleton, script, options, 0.0,
                         [&](const HandSimState& s) { watch.observe(s); });
  run.loss = watch.loss(run.report.held);
  run.pushed_mm = watch.pushed_mm();
  run.grip_at_lift_n = watch.grip_at_lift_n();
  run.touch_lead_ms = watch.touch_lead_ms();
  run.turn_at_touch_deg = watch.turn_at_touch_deg();
  return run;
}

}  // namespace handlab::sim
