// The simulator's rigid bodies and contact against known answers: inertia of solids, the
// box distance, a dropped cube (free fall at g, then rest on the floor), a cube on a tilted
// floor (sticks below atan(mu), slides above), a pushed cube sliding to a stop, spinning cubes
// tumbling to rest, and a cube pressed into the floor let go; settle_cube's measures of a
// kicked cube. The cube on the floor is stepped as the hand's simulator steps a cube no flesh
// touches (lone_cube.h): a moving one in the free cube's substeps.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/sim/box_distance.h"
#include "core/sim/free_cube.h"
#include "core/sim/hand_simulator.h"
#include "core/sim/rigid_body.h"
#include "core/sim/step_solver.h"
#include "core/task/cube_settle.h"
#include "tests/core/sim/lone_cube.h"

namespace handlab::sim {
namespace {

TEST(RigidBody, SolidInertias) {
  const RigidInertia box = box_inertia(Eigen::Vector3d(0.02, 0.04, 0.06), 1000.0);
  EXPECT_NEAR(box.mass, 0.048, 1e-15);
  EXPECT_NEAR(box.inertia(0, 0), 0.048 / 12 * (0.04 * 0.04 + 0.06 * 0.06), 1e-18);
  // A capsule shrinks to a sphere (2/5 m r^2) and stretches to a rod (m L^2 / 12).
  const RigidInertia sphere =
      capsule_inertia(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.01, 1000.0);
  EXPECT_NEAR(sphere.mass, 1000.0 * 4.0 / 3.0 * std::numbers::pi * 1e-6, 1e-15);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sphere.inertia(k, k), 0.4 * sphere.mass * 1e-4, 1e-15);
  const RigidInertia rod =
      capsule_inertia(Eigen::Vector3d(0, -0.5, 0), Eigen::Vector3d(0, 0.5, 0), 1e-4, 1000.0);
  EXPECT_NEAR(rod.inertia(0, 0) / (rod.mass / 12.0), 1.0, 1e-3);
  EXPECT_NEAR(rod.inertia(1, 1) / rod.inertia(0, 0), 0.0, 1e-6);
  // Two parts as one: parallel axes.
  RigidInertia a = box_inertia(Eigen::Vector3d::Constant(0.01), 1000.0), b = a;
  a.centre = Eigen::Vector3d(-0.05, 0, 0);
  b.centre = Eigen::Vector3d(0.05, 0, 0);
  const RigidInertia both = combine({a, b});
  EXPECT_NEAR(both.centre.norm(), 0.0, 1e-15);
  EXPECT_NEAR(both.inertia(1, 1), 2 * a.inertia(1, 1) + 2 * a.mass * 0.0025, 1e-15);
  EXPECT_NEAR(both.inertia(0, 0), 2 * a.inertia(0, 0), 1e-15);
}

TEST(RigidBody, RotationVectorRoundTrips) {
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0.3, -0.2, 0.1), Eigen::Vector3d(0, 0, 3.1),
                                   Eigen::Vector3d(1e-9, 0, 0), Eigen::Vector3d::Zero().eval()}) {
    EXPECT_LT((rotation_vector(rotation_from_vector(v)) - v).norm(), 1e-12) << v.transpose();
  }
  const Eigen::Vector3d u(0.1, 0.2, 0.3), w(-0.3, 0.5, 0.2);
  EXPECT_LT((cross_matrix(u) * w - u.cross(w)).norm(), 1e-15);
}

TEST(BoxDistance, OutsideInsideAndOnEdges) {
  const Eigen::Vector3d half(0.01, 0.02, 0.03);
  BoxProximity p = box_proximity(half, Eigen::Vector3d(0.015, 0, 0));
  EXPECT_NEAR(p.distance, 0.005, 1e-15);
  EXPECT_EQ(p.normal, Eigen::Vector3d::UnitX());
  p = box_proximity(half, Eigen::Vector3d(0.013, 0.024, 0));  // beyond an edge
  EXPECT_NEAR(p.distance, 0.005, 1e-15);
  EXPECT_LT((p.closest - Eigen::Vector3d(0.01, 0.02, 0)).norm(), 1e-15);
  p = box_proximity(half, Eigen::Vector3d(0.0, -0.018, 0.01));  // inside, nearest face -y
  EXPECT_NEAR(p.distance, -0.002, 1e-15);
  EXPECT_EQ(p.normal, -Eigen::Vector3d::UnitY());
  EXPECT_LT((p.closest - Eigen::Vector3d(0.0, -0.02, 0.01)).norm(), 1e-15);
}

// Far points are told by the axes' gaps alone, and never one within the reach: contacts are
// searched where box_proximity's distance is within it.
TEST(BoxDistance, BeyondTellsFarPointsAndNoNearOne) {
  const Eigen::Vector3d half(0.005, 0.005, 0.005);
  const double reach = 0.002;
  // Along an axis: beyond at a gap past the reach, not at the reach or just within it.
  EXPECT_TRUE(beyond_box(half, Eigen::Vector3d(0.005 + 1.001 * reach, 0, 0), reach));
  EXPECT_FALSE(beyond_box(half, Eigen::Vector3d(0.005 + reach, 0, 0), reach));
  EXPECT_FALSE(beyond_box(half, Eigen::Vector3d(0, -0.005 - 0.999999 * reach, 0), reach));
  EXPECT_FALSE(beyond_box(half, Eigen::Vector3d::Zero(), reach));  // inside
  // Beyond a corner each axis's gap is within the reach and the distance past it: a bound,
  // never told beyond where the distance is within.
  const Eigen::Vector3d corner(0.0063, 0.0063, 0.0063);
  EXPECT_FALSE(beyond_box(half, corner, reach));
  EXPECT_GT(box_proximity(half, corner).distance, reach);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> place(-0.012, 0.012), length(1e-5, 0.004);
  int beyond = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d q(place(random), place(random), place(random));
    const double r = length(random);
    if (!beyond_box(half, q, r)) continue;
    ++beyond;
    ASSERT_GE(box_proximity(half, q).distance, r) << q.transpose() << " reach " << r;
  }
  EXPECT_GT(beyond, 10000);
}

// A point inside pushed out through a face it names, however near another face it lies; the
// face a point lies farthest outside of (inside, the nearest).
TEST(BoxDistance, ThroughAGivenFace) {
  const Eigen::Vector3d half(0.01, 0.02, 0.03);
  const Eigen::Vector3d near_bottom(0.009, -0.0197, 0.0);  // 1 mm inside +x, 0.3 mm above -y
  EXPECT_EQ(box_face(half, near_bottom), 2);               // -y: the nearest
  EXPECT_EQ(box_face(half, Eigen::Vector3d(0.0102, -0.0199, 0)), 1) << "outside +x, not -y";
  EXPECT_EQ(box_face(half, Eigen::Vector3d(0, 0, 0.031)), 5);
  BoxProximity p = box_proximity_through(half, near_bottom, 1);
  EXPECT_NEAR(p.distance, -0.001, 1e-15);
  EXPECT_EQ(p.normal, Eigen::Vector3d::UnitX());
  EXPECT_LT((p.closest - Eigen::Vector3d(0.01, -0.0197, 0)).norm(), 1e-15);
  p = box_proximity_through(half, near_bottom, 2);
  EXPECT_NEAR(p.distance, -0.0003, 1e-15);
  EXPECT_EQ(p.normal, -Eigen::Vector3d::UnitY());
  const Eigen::Vector3d outside(0.013, 0.024, 0);  // outside: the box's distance, any face
  p = box_proximity_through(half, outside, 4);
  EXPECT_NEAR(p.distance, box_proximity(half, outside).distance, 1e-15);
  EXPECT_EQ(p.normal, box_proximity(half, outside).normal);
}

// The lowest point of the cube above the floor.
double clearance(const HandSimModel& m, const HandSimState& s) {
  double lowest = INFINITY;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    lowest = std::min(
        lowest, m.parameters.floor_normal.dot(s.cube_pose.point(corner.cwiseProduct(m.cube_half))) -
                    m.parameters.floor_height);
  }
  return lowest;
}

class DroppedCube : public testing::TestWithParam<double> {};

TEST_P(DroppedCube, FallsAtGThenRests) {
  SimParameters p;
  p.cube_size = GetParam();
  const HandSimModel m = lone_cube_model(p);
  HandSimulator sim(m);
  RigidPose start;
  start.position = Eigen::Vector3d(0, 0.1 + p.cube_size / 2, 0);
  HandSimState s = lone_cube_state(m, start);
  const double h = p.time_step, g = 9.81, drop = 0.1;
  // Backward Euler is exact on free fall in any number of substeps: after i steps the velocity
  // is g i h, and in the free cube's n substeps the cube has dropped g h^2 i (i + 1/n) / 2. In
  // the first step that would take it past the floor it lands (0.150 s; sqrt(2 drop / g) =
  // 0.143 s), and by the step after the floor has taken its speed (a light cube's landing may
  // rebound a little within the substeps).
  const double n = FreeCubeStepper::kSubsteps;
  int landing = 1;
  while (g * h * h * landing * (landing + 1 / n) / 2 < drop) ++landing;
  for (int i = 1; i <= 240; ++i) {
    sim.step(s, {});
    if (i < landing) {
      EXPECT_NEAR(-s.cube_velocity.linear.y() / (g * i * h), 1.0, 0.01) << "step " << i;
    } else if (i == landing + 1) {
      EXPECT_LT(s.cube_velocity.linear.norm(), 0.1 * g * landing * h) << "it should have landed";
    }
  }
  double highest = -INFINITY, deepest = INFINITY;
  for (int i = 0; i < 240; ++i) {
    sim.step(s, {});
    highest = std::max(highest, clearance(m, s));
    deepest = std::min(deepest, clearance(m, s));
  }
  EXPECT_LT(highest, 1e-4) << "bounced away";
  EXPECT_GT(deepest, -0.5e-3) << "sank";
  EXPECT_LT(s.cube_velocity.linear.norm(), 1e-3);
  EXPECT_LT(s.cube_velocity.angular.norm(), 1e-2);
}

INSTANTIATE_TEST_SUITE_P(StudyCubes, DroppedCube, testing::Values(0.01, 0.06));

// The 6 cm cube alone at the cube's substep (1/1920 s) on corners stiffened by `stiffening`.
SimParameters floor_with(double stiffening) {
  SimParameters p;
  p.cube_size = 0.06;
  p.time_step = 1.0 / 1920;
  p.cube_floor_stiffening = stiffening;
  return p;
}

double cube_weight(const SimParameters& p) {
  return make_cube_sim_model(p).cube.mass * p.gravity.norm();
}

// How deep a corner presses into the floor under `force`: k d + k3 d^2 = force.
double corner_depth(const SimParameters& p, double force) {
  const double k = p.cube_floor_stiffness, k3 = p.cube_floor_stiffening;
  return k3 > 0 ? (std::sqrt(k * k + 4 * k3 * force) - k) / (2 * k3) : force / k;
}

// The 6 cm cube stepped alone from `sunk` below where it touches the floor, level and at rest,
// for `seconds`: the highest and the last height of its centre above where it touches.
std::pair<double, double> heights_from(const SimParameters& p, double sunk, double seconds) {
  const HandSimModel m = make_cube_sim_model(p);
  RigidPose pose;
  pose.position = Eigen::Vector3d(0, p.cube_size / 2 - sunk, 0);
  HandSimState s = initial_state(m, {}, Eigen::Isometry3d::Identity(), pose), next;
  StepSolver solver(m, single_threaded());
  double highest = -INFINITY;
  for (int i = 0; i < int(std::lround(seconds / p.time_step)); ++i) {
    solver.step(s, {}, next);
    std::swap(s, next);
    highest = std::max(highest, s.cube_pose.position.y() - p.cube_size / 2);
  }
  return {highest, s.cube_pose.position.y() - p.cube_size / 2};
}

// Resting, the cube sinks as far as the corners' law says under its weight: 26.5 um on the
// linear corners (10^4 N/m), 4.7 um with the stiffening at 10^10 N/m^2.
TEST(PressedCube, RestsAsDeepAsTheCornersLawSays) {
  for (double stiffening : {0.0, 1e10}) {
    const SimParameters p = floor_with(stiffening);
    const double rest = -heights_from(p, 0.0, 0.5).second;
    EXPECT_NEAR(rest / corner_depth(p, cube_weight(p) / 4), 1.0, 0.05)
        << "stiffening " << stiffening;
  }
}

// Pressed into the floor as a hand's 143 N on its top (and its weight) leave it, then let go
// and stepped at the cube's substep: the press's energy in the corners comes back
// as a throw. The linear corners (3.6 mm deep) store 0.26 J, which would lift it 24 cm; with
// the stiffening (59 um deep) 2.9 mJ, 2.7 mm.
TEST(PressedCube, TheLinearFloorThrowsItTheStiffFloorDoesNot) {
  const auto rise = [](double stiffening) {
    const SimParameters p = floor_with(stiffening);
    return heights_from(p, corner_depth(p, (143.0 + cube_weight(p)) / 4), 0.5).first;
  };
  EXPECT_GT(rise(0.0), 0.1);
  EXPECT_LT(rise(1e10), 2.7e-3);
}

// A cube resting on a floor tilted by `tilt` about z: how far it slides in `seconds`.
double slide_on_tilted_floor(double tilt, double seconds, double* creep_speed = nullptr) {
  SimParameters p;
  p.cube_size = 0.06;
  p.floor_normal = Eigen::Vector3d(-std::sin(tilt), std::cos(tilt), 0);
  const HandSimModel m = lone_cube_model(p);
  HandSimulator sim(m);
  RigidPose start;
  start.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitZ()));
  start.position = p.floor_normal * (p.cube_size / 2);
  HandSimState s = lone_cube_state(m, start);
  const int steps = int(std::lround(seconds / p.time_step));
  Eigen::Vector3d settled = s.cube_pose.position;
  for (int i = 0; i < steps; ++i) {
    sim.step(s, {});
    if (i == steps / 2) settled = s.cube_pose.position;
  }
  if (creep_speed) *creep_speed = (s.cube_pose.position - settled).norm() / (seconds / 2);
  return (s.cube_pose.position - start.position).norm();
}

TEST(TiltedFloor, CubeSticksBelowTheFrictionAngleAndSlidesAbove) {
  const double mu = SimParameters{}.friction, friction_angle = std::atan(mu);
  double creep = 0.0;
  slide_on_tilted_floor(0.8 * friction_angle, 2.0, &creep);
  EXPECT_LT(creep, 1e-3) << "m/s at 0.8 of the friction angle";
  // Onset: the first angle (0.25 degree steps) at which it slides more than 1 cm in 1 s.
  const double degree = std::numbers::pi / 180;
  double onset = NAN;
  for (double a = friction_angle - 3 * degree; a < friction_angle + 3 * degree; a += 0.25 * degree)
    if (slide_on_tilted_floor(a, 1.0) > 0.01) {
      onset = a;
      break;
    }
  ASSERT_FALSE(std::isnan(onset)) << "never slid";
  std::cout << "friction angle " << friction_angle / degree << " deg; slides from "
            << onset / degree << " deg; creep at 0.8 of it " << creep * 1000 << " mm/s\n";
  EXPECT_NEAR(onset / degree, friction_angle / degree, 1.0);
}

// A cube pushed along the floor slides to a stop under Coulomb's kinetic friction: backward
// Euler takes mu g h off its speed every step (h: the free cube's substep), so it covers
// h sum_k max(0, v0 - k mu g h).
class SlidingCube : public testing::TestWithParam<double> {};

TEST_P(SlidingCube, StopsUnderKineticFriction) {
  SimParameters p;
  p.cube_size = GetParam();
  const HandSimModel m = lone_cube_model(p);
  HandSimulator sim(m);
  RigidPose start;
  start.position = Eigen::Vector3d(0, p.cube_size / 2, 0);
  HandSimState s = lone_cube_state(m, start);
  for (int i = 0; i < 30; ++i) sim.step(s, {});  // settled, its anchors in place
  const double v0 = 0.5, h = p.time_step / FreeCubeStepper::kSubsteps;
  const double decrement = p.friction * 9.81 * h;
  double expected = 0.0;
  for (int k = 1; v0 - k * decrement > 0; ++k) expected += h * (v0 - k * decrement);
  s.cube_velocity.linear = Eigen::Vector3d(v0, 0, 0);
  const double x0 = s.cube_pose.position.x();
  for (int i = 0; i < 60; ++i) sim.step(s, {});
  const double distance = s.cube_pose.position.x() - x0, bound = v0 * v0 / (2 * p.friction * 9.81);
  std::cout << "slid " << distance * 1000 << " mm, backward Euler with Coulomb: " << expected * 1000
            << " mm, continuous: " << bound * 1000 << " mm\n";
  EXPECT_NEAR(distance, expected, 0.02 * expected);
  EXPECT_LE(distance, bound) << "no further than its energy allows";
  EXPECT_LT(s.cube_velocity.linear.norm(), 1e-3) << "it should have stopped";
  EXPECT_LT(s.cube_velocity.angular.norm(), 1e-2);
  EXPECT_LT(std::abs(s.cube_pose.position.z()), 1e-4) << "it should slide straight";
}

INSTANTIATE_TEST_SUITE_P(StudyCubes, SlidingCube, testing::Values(0.01, 0.06));

// A light cube flicked by the fingers can leave them spinning fast. Landing on the floor, it
// tumbles to a stop. Spun at a good part of a quarter turn a step, its corner contacts aliased
// at the hand's step and the floor drove it on: a 1 cm cube rolled for metres, its spin
// growing; on the stiffened floor with one Newton iteration a substep a landing corner threw it
// back up (7.9 times its energy, rolling at 150 rad/s). Each throw alone is chaotic (where a
// corner lands), so sixty: thrown at 1 m/s, spun at 10-200 rad/s about three axes. (A corner
// landing while the cube rolls can hand it back some energy, up to 8 % here: penalty contact
// with anchored friction is not exactly dissipative on impact. A runaway is what must not
// happen.)
TEST(SpinningCube, TumblesToRestWithoutRunningAway) {
  SimParameters p;
  p.cube_size = 0.01;
  const HandSimModel m = lone_cube_model(p);
  const Eigen::Vector3d axes[] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                  Eigen::Vector3d(0.5, 0, 1).normalized()};
  double worst = 0.0, furthest = 0.0;
  for (const Eigen::Vector3d& axis : axes)
    for (double spin = 10; spin <= 200; spin += 10) {
      HandSimulator sim(m);
      RigidPose start;
      start.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
      start.position = Eigen::Vector3d(0, 0.008, 0);  // its lowest corner just above the floor
      HandSimState s = lone_cube_state(m, start);
      s.cube_velocity.linear = Eigen::Vector3d(1.0, 0, 0.3);
      s.cube_velocity.angular = spin * axis;
      const double initial = cube_energy(m, s);
      double highest = initial;
      for (int i = 0; i < 180; ++i) {
        sim.step(s, {});
        highest = std::max(highest, cube_energy(m, s));
      }
      const double travelled = (s.cube_pose.position - start.position).norm();
      worst = std::max(worst, highest / initial);
      furthest = std::max(furthest, travelled);
      const std::string name = std::to_string(int(spin)) + " rad/s about (" +
                               std::to_string(axis.x()) + ", 0, " + std::to_string(axis.z()) + ")";
      EXPECT_LE(highest, 1.25 * initial) << name << ": it gained energy";
      EXPECT_LT(s.cube_velocity.linear.norm(), 1e-3) << name << ": still moving after 1.5 s";
      EXPECT_LT(s.cube_velocity.angular.norm(), 1e-2) << name;
      EXPECT_LT(travelled, 0.5) << name << ": m travelled";
    }
  std::cout << "sixty throws: at most " << worst << " times the energy thrown with, at most "
            << furthest * 1000 << " mm away\n";
}

// settle_cube's measures where they can be worked out, on the cube as the simulator steps it.
// A flat push (0.5 m/s, no spin): its energy, the slide that energy allows, the slide backward
// Euler with Coulomb gives in the free cube's substeps (mu g h off the speed every substep;
// along the kick's heading, a little across x, within 15 %) and, by the rule for rest (within
// 0.1 mm of the end), the time at which that slide comes within 0.1 mm of its end, to the
// report's step (the hand's); its centre stays within 10 um of its rest (the 6 cm cube rests
// 4.7 um deep on the stiffened corners; more would be a hop). A spin alone: E0 is the rotational
// energy. A run too short to see it still: no rest.
TEST(CubeSettle, MeasuresWhatCanBeWorkedOut) {
  for (double size : {0.01, 0.06}) {
    SimParameters p;
    p.cube_size = size;
    const double v0 = 0.5, h = p.time_step / FreeCubeStepper::kSubsteps;
    const double decrement = p.friction * 9.81 * h;
    const HandSimModel m = lone_cube_model(p);
    RigidPose on_floor;
    on_floor.position = Eigen::Vector3d(0, size / 2, 0);
    const CubeSettleReport r = settle_cube(m, lone_cube_state(m, on_floor), {v0, 0.0}, {}, 1.0);
    std::vector<double> path = {0.0};  // backward Euler's slide, substep by substep
    for (int k = 1; v0 - k * decrement > 0; ++k)
      path.push_back(path.back() + h * (v0 - k * decrement));
    int near_end = 0;
    while (path.back() - path[std::size_t(near_end)] > 1e-4) ++near_end;
    const double mass = p.cube_density * size * size * size;
    std::cout << size << ": slid " << r.travelled * 1000 << " mm (backward Euler "
              << path.back() * 1000 << ", energy's bound " << r.slide_bound * 1000
              << "), at rest after " << r.rest_time << " s (" << near_end * h << "), rose "
              << r.highest_rise * 1e6 << " um\n";
    EXPECT_NEAR(r.start_energy, 0.5 * mass * v0 * v0, 1e-9 * r.start_energy);
    EXPECT_NEAR(r.slide_bound, v0 * v0 / (2 * p.friction * 9.81), 1e-9);
    EXPECT_LE(r.travelled, r.slide_bound) << size;
    EXPECT_NEAR(r.travelled, path.back(), 0.15 * path.back()) << size;
    EXPECT_NEAR(r.rest_time, near_end * h, p.time_step) << size;
    EXPECT_LT(r.highest_rise, 1e-5) << size;
    EXPECT_LE(r.highest_energy, r.start_energy * (1 + 1e-9)) << size;
  }
  SimParameters p;
  const double w = 3.0, inertia = p.cube_density * std::pow(p.cube_size, 5) / 6;
  EXPECT_NEAR(settle_cube(p, {0.0, w}, {}, 0.5).start_energy, 0.5 * inertia * w * w,
              1e-9 * inertia * w * w);
  EXPECT_EQ(settle_cube(p, {0.2, 0.0}, {}, 0.05).rest_time, -1.0) << "0.05 s: never 0.1 s still";
}

// A step's later passes start from its first pass's start, kept by its first Newton iteration.
TEST(StepSolver, RejectsNoNewtonIteration) {
  const HandSimModel model = lone_cube_model(SimParameters{});
  SimOptions options;
  options.newton_iterations = 0;
  EXPECT_THROW((StepSolver{model, options}), std::invalid_argument);
  options.newton_iterations = 1;
  EXPECT_NO_THROW((StepSolver{model, options}));
}

TEST(HandSimulator, RejectsTargetsThatAreNotFinite) {
  const HandSimModel m = make_cube_sim_model();
  HandSimulator sim(m);
  HandSimState s = initial_state(m, {}, Eigen::Isometry3d::Identity(), RigidPose{});
  EXPECT_THROW(sim.step(s, {RigidPose{}}), std::invalid_argument);  // the cube model has no bones
}

}  // namespace
}  // namespace handlab::sim
