#include "core/task/tracker_jitter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace handlab::sim {
namespace {

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& r) {
  const Eigen::AngleAxisd a(r);
  return a.angle() * a.axis();
}

}  // namespace

double PoseJitter::root_rms() const {
  double sum = 0.0;
  for (const Eigen::Vector3d& r : root) sum += r.squaredNorm() / 3;
  return root.empty() ? 0.0 : std::sqrt(sum / double(root.size()));
}

double PoseJitter::angle_rms() const {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Eigen::VectorXd& a : angles) {
    sum += a.squaredNorm();
    n += std::size_t(a.size());
  }
  return n == 0 ? 0.0 : std::sqrt(sum / double(n));
}

void PoseJitter::apply(double t, double scale, hand::HandPose& pose) const {
  if (times.empty() || scale == 0.0) return;
  if (pose.angles.size() != angles.front().size())
    throw std::invalid_argument("PoseJitter: a recording's jitter of another hand's joints");
  const double looped = std::fmod(std::max(t, 0.0), duration() > 0 ? duration() : 1.0);
  const std::size_t k =
      std::size_t(std::upper_bound(times.begin(), times.end(), looped) - times.begin() - 1);
  pose.angles += scale * angles[k];
  pose.root_position += scale * root[k];
  const Eigen::Vector3d v = scale * turn[k];
  if (v.norm() > 0)
    pose.root_rotation = Eigen::AngleAxisd(v.norm(), v.normalized()) * pose.root_rotation;
}

PoseJitter pose_jitter(const std::vector<double>& times, const std::vector<hand::HandPose>& poses,
                       double window) {
  if (poses.size() < 2 || times.size() != poses.size())
    throw std::invalid_argument("pose_jitter: fewer than two poses");
  PoseJitter j;
  std::size_t from = 0, to = 0;  // the poses within half a window of pose k: [from, to)
  double start = 0.0;            // the first pose kept
  for (std::size_t k = 0; k < poses.size(); ++k) {
    // Where the window is whole: a one-sided average at the ends would lag a moving hand.
    if (times[k] - times.front() < window / 2 || times.back() - times[k] < window / 2) continue;
    while (times[from] < times[k] - window / 2) ++from;
    while (to < poses.size() && times[to] <= times[k] + window / 2) ++to;
    Eigen::VectorXd angles = Eigen::VectorXd::Zero(poses[k].angles.size());
    Eigen::Vector3d root = Eigen::Vector3d::Zero(), turn = Eigen::Vector3d::Zero();
    for (std::size_t i = from; i < to; ++i) {
      angles += poses[i].angles;
      root += poses[i].root_position;
      // The others' rotations seen from pose k's: small, so their vectors average.
      turn += rotation_vector(poses[i].root_rotation * poses[k].root_rotation.transpose());
    }
    const double n = double(to - from);
    if (j.times.empty()) start = times[k];
    j.times.push_back(times[k] - start);
    j.angles.push_back(poses[k].angles - angles / n);
    j.root.push_back(poses[k].root_position - root / n);
    j.turn.push_back(-turn / n);
  }
  if (j.times.size() < 2) throw std::invalid_argument("pose_jitter: shorter than its window");
  return j;
}

}  // namespace handlab::sim
