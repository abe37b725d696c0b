#include "core/task/cube_settle.h"

#include <algorithm>
#include <vector>

#include "core/sim/hand_simulator.h"

namespace handlab::sim {
namespace {

// Within this of where it ends, from this long before the run ends, it lies still.
constexpr double kStillMove = 1e-4, kStillTurn = 0.01, kStillFor = 0.1;  // m, rad, s

double weight_per_height(const HandSimModel& model) {  // m g along the floor's normal (N)
  const SimParameters& p = model.parameters;
  return -model.cube.mass * p.gravity.dot(p.floor_normal.normalized());
}

}  // namespace

double cube_energy(const HandSimModel& model, const HandSimState& s) {
  const Eigen::Vector3d& w = s.cube_velocity.angular;
  const Eigen::Matrix3d r = s.cube_pose.rotation.toRotationMatrix();
  const SimParameters& p = model.parameters;
  const double height = p.floor_normal.normalized().dot(s.cube_pose.position) - p.floor_height;
  return 0.5 * model.cube.mass * s.cube_velocity.linear.squaredNorm() +
         0.5 * w.dot(r * model.cube.inertia * r.transpose() * w) +
         weight_per_height(model) * height;
}

CubeSettleReport settle_cube(const SimParameters& parameters, const CubeKick& kick,
                             const SimOptions& options, double duration) {
  const HandSimModel model = make_cube_sim_model(parameters);
  RigidPose start;
  start.position =
      (parameters.floor_height + parameters.cube_size / 2) * parameters.floor_normal.normalized();
  return settle_cube(model, initial_state(model, {}, Eigen::Isometry3d::Identity(), start), kick,
                     options, duration);
}

CubeSettleReport settle_cube(const HandSimModel& model, HandSimState s, const CubeKick& kick,
                             const SimOptions& options, double duration) {
  const SimParameters& parameters = model.parameters;
  HandSimulator simulator(model, options);
  const Eigen::Vector3d up = parameters.floor_normal.normalized();
  const double h = parameters.time_step;
  for (int i = 0; i * h < 0.25; ++i) simulator.step(s, {});
  const Eigen::Vector3d rest = s.cube_pose.position;
  const double rest_energy = cube_energy(model, s);
  s.cube_velocity.linear = kick.speed * Eigen::Vector3d(1, 0, 0.3).normalized();
  s.cube_velocity.angular = kick.spin * Eigen::Vector3d(0.5, 0, 1).normalized();
  CubeSettleReport report;
  report.start_energy = report.highest_energy = cube_energy(model, s) - rest_energy;
  report.slide_bound = report.start_energy / (parameters.friction * weight_per_height(model));
  std::vector<RigidPose> poses = {s.cube_pose};  // poses[i]: i steps after the kick
  for (int i = 0; i * h < duration; ++i) {
    simulator.step(s, {});
    report.highest_energy = std::max(report.highest_energy, cube_energy(model, s) - rest_energy);
    report.highest_rise = std::max(report.highest_rise, up.dot(s.cube_pose.position - rest));
    poses.push_back(s.cube_pose);
  }
  const RigidPose& end = poses.back();
  int last_away = -1;
  for (int i = 0; i < int(poses.size()); ++i)
    if ((poses[std::size_t(i)].position - end.position).norm() > kStillMove ||
        poses[std::size_t(i)].rotation.angularDistance(end.rotation) > kStillTurn)
      last_away = i;
  const int still_from = last_away + 1, last = int(poses.size()) - 1;
  if ((last - still_from) * h >= kStillFor - 0.5 * h) report.rest_time = still_from * h;
  const Eigen::Vector3d moved = end.position - rest;
  report.travelled = (moved - up.dot(moved) * up).norm();
  return report;
}

}  // namespace handlab::sim
