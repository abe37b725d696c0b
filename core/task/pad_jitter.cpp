#include "core/task/pad_jitter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace handlab::sim {
namespace {

double rms(double sum_of_squares, int n) {
  return std::sqrt(sum_of_squares / n);
}

}  // namespace

PadJitter pad_jitter(const hand::Skeleton& skeleton, const hand::HandPose& pinch,
                     const PinchPads& pads, const PoseJitter& jitter, double scale,
                     double time_step) {
  const int bones = int(skeleton.bones.size());
  if (pads.thumb_bone < 0 || pads.thumb_bone >= bones || pads.index_bone < 0 ||
      pads.index_bone >= bones)
    throw std::invalid_argument("pad_jitter: a pad's bone is not in the skeleton");
  if (!(time_step > 0)) throw std::invalid_argument("pad_jitter: the time step must be above 0");
  // One pass, [0, duration): the step at the duration would take the first frame again.
  const int steps = int(std::ceil(jitter.duration() / time_step - 1e-9));
  if (steps < 2) throw std::invalid_argument("pad_jitter: the jitter is shorter than two steps");

  hand::BoneFrames frames;
  hand::forward_kinematics(skeleton, pinch, frames);
  const PadPoints still = pad_points(frames, pads);
  const Eigen::Vector3d axis = (still.index - still.thumb).normalized();
  PadJitter out;
  out.scale = scale;
  double thumb = 0, index = 0, along = 0, across = 0, speed = 0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (int k = 0; k < steps; ++k) {
    hand::HandPose pose = pinch;
    jitter.apply(k * time_step, scale, pose);
    hand::forward_kinematics(skeleton, pose, frames);
    const PadPoints p = pad_points(frames, pads);
    const Eigen::Vector3d relative = (p.index - p.thumb) - (still.index - still.thumb);
    const double a = relative.dot(axis);
    thumb += (p.thumb - still.thumb).squaredNorm();
    index += (p.index - still.index).squaredNorm();
    along += a * a;
    across += (relative - a * axis).squaredNorm();
    if (k > 0) {
      const double v = (relative - previous).norm() / time_step;
      speed += v * v;
      out.relative_speed_max = std::max(out.relative_speed_max, v);
    }
    previous = relative;
  }
  out.thumb_rms = rms(thumb, steps);
  out.index_rms = rms(index, steps);
  out.along_rms = rms(along, steps);
  out.across_rms = rms(across, steps);
  out.relative_speed_rms = rms(speed, steps - 1);
  return out;
}

}  // namespace handlab::sim
