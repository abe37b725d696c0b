#include "core/sim/cube_substeps.h"

#include <algorithm>
#include <utility>

#include "core/sim/box_distance.h"
#include "core/sim/contact.h"
#include "core/sim/contact_substeps.h"
#include "core/sim/step_solver.h"

namespace handlab::sim {
namespace {

using FleshPoint = CubeSubsteps::FleshPoint;

Eigen::Vector3d flesh_point_at(const HandSimModel& hand, const HandSimState& s,
                               const FleshPoint& p) {
  return p.sample ? skin_sample_position(hand, s, p.index) : s.node_position[std::size_t(p.index)];
}

// The points within `reach` of the cube at the start beyond what they and the cube move in the
// step: nodes first, then samples, each in ascending order (so that anchor lists stay sorted
// by point).
std::vector<FleshPoint> near_points(const HandSimModel& hand, const HandSimState& start,
                                    const HandSimState& end, double reach) {
  const double h = hand.parameters.time_step;
  const RigidVelocity& v = start.cube_velocity;
  const double cube_travel = std::max(
      h * (v.linear.norm() + v.angular.norm() * hand.cube_half.norm()),
      (end.cube_pose.position - start.cube_pose.position).norm() +
          end.cube_pose.rotation.angularDistance(start.cube_pose.rotation) * hand.cube_half.norm());
  const Eigen::Quaterniond inverse = start.cube_pose.rotation.conjugate();
  std::vector<FleshPoint> points;
  const double radius = hand.cube_half.norm();
  auto consider = [&](const FleshPoint& p) {
    const Eigen::Vector3d x0 = flesh_point_at(hand, start, p), x1 = flesh_point_at(hand, end, p);
    const double band = reach + (x1 - x0).norm() + cube_travel;
    if ((x0 - start.cube_pose.position).norm() - radius >= band) return;  // beyond its sphere
    const Eigen::Vector3d q = inverse * (x0 - start.cube_pose.position);
    if (!beyond_box(hand.cube_half, q, band) && box_proximity(hand.cube_half, q).distance < band)
      points.push_back(p);
  };
  for (int node : hand.surface_nodes) consider({false, node});
  for (int i = 0; i < int(hand.skin_samples.size()); ++i) consider({true, i});
  return points;
}

// The cube, the floor and the points as kinematic nodes of no flesh, at the substep's time step:
// the cube's six unknowns are the solve's.
HandSimModel substep_model(const HandSimModel& hand, std::size_t points, int substeps) {
  SimParameters p = hand.parameters;
  p.time_step /= substeps;
  p.hand_floor_contact = false;
  p.contact_time_step = p.contact_substep_window = 0.0;
  HandSimModel m = make_cube_sim_model(p);
  m.rest.assign(points, Eigen::Vector3d::Zero());
  m.node_mass.assign(points, 0.0);
  m.kinematic_nodes = true;
  for (int i = 0; i < int(points); ++i) m.surface_nodes.push_back(i);
  m.cube_contact_share = hand.cube_contact_share;  // a node and a sample alike
  return m;
}

}  // namespace

struct CubeSubsteps::Points {
  std::vector<FleshPoint> points;
  HandSimModel model;
  StepSolver solver;
  Points(const HandSimModel& hand, std::vector<FleshPoint> p, int substeps)
      : points(std::move(p)),
        model(substep_model(hand, points.size(), substeps)),
        solver(model, single_threaded()) {}
};

bool CubeSubsteps::enabled(const SimParameters& parameters) {
  return parameters.contact_substeps_cube && contact_substep_count(parameters) > 1;
}

CubeSubsteps::CubeSubsteps(const HandSimModel& hand)
    : hand_(hand), substeps_(contact_substep_count(hand.parameters)) {}
CubeSubsteps::~CubeSubsteps() = default;

SimStepReport CubeSubsteps::step(const HandSimState& start, HandSimState& result) {
  const std::vector<FleshPoint> near = near_points(hand_, start, result, kReach);
  if (!points_ ||
      !std::includes(points_->points.begin(), points_->points.end(), near.begin(), near.end()))
    points_ =
        std::make_unique<Points>(hand_, near_points(hand_, start, result, 2 * kReach), substeps_);
  const std::vector<FleshPoint>& points = points_->points;
  const HandSimModel& model = points_->model;
  StepSolver& solver = points_->solver;

  HandSimState cube = initial_state(model, {}, Eigen::Isometry3d::Identity(), start.cube_pose);
  cube.time = start.time;
  cube.cube_velocity = start.cube_velocity;
  cube.corner_floor = start.corner_floor;
  std::vector<Eigen::Vector3d> from(points.size()), to(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const FleshPoint& p = points[i];
    from[i] = cube.node_position[i] = flesh_point_at(hand_, start, p);
    to[i] = flesh_point_at(hand_, result, p);
    const ContactAnchor* a = find_anchor(p.sample ? start.sample_cube : start.node_cube, p.index);
    if (a) cube.node_cube.push_back({int(i), a->anchor, a->face});
  }

  const double h = model.parameters.time_step;
  SimStepReport report;
  HandSimState next;
  for (int k = 1; k <= substeps_; ++k) {
    const double t = double(k) / substeps_;
    // Carried by its velocity, a point lands on its path's next place.
    for (std::size_t i = 0; i < points.size(); ++i)
      cube.node_velocity[i] = ((1 - t) * from[i] + t * to[i] - cube.node_position[i]) / h;
    report = solver.step(cube, {}, next);
    for (std::size_t i = 0; i < points.size(); ++i)
      next.node_position[i] = (1 - t) * from[i] + t * to[i];
    std::swap(cube, next);
  }

  result.cube_pose = cube.cube_pose;
  result.cube_velocity = cube.cube_velocity;
  result.corner_floor = cube.corner_floor;
  result.node_cube.clear();
  result.sample_cube.clear();
  for (const ContactAnchor& a : cube.node_cube) {
    const FleshPoint& p = points[std::size_t(a.point)];
    (p.sample ? result.sample_cube : result.node_cube).push_back({p.index, a.anchor, a.face});
  }
  return report;
}

}  // namespace handlab::sim
