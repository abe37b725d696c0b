#include <random>

#include <gtest/gtest.h>

#include "core/hand/simulated_hand.h"
#include "core/hand/tracked_hand.h"
#include "core/retarget/fingertip_solver.h"
#include "core/retarget/retargeter.h"

namespace handlab::retarget {
namespace {

using hand::HandPose;
using hand::Skeleton;

HandPose random_interior_pose(const Skeleton& s, std::mt19937& rng, double spread = 0.7) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  HandPose pose = HandPose::rest(s);
  pose.root_position = Eigen::Vector3d(0.02, 0.2, -0.03);
  pose.root_rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 1, 0.2).normalized()).toRotationMatrix();
  for (std::size_t k = 0; k < s.dofs.size(); ++k) {
    const double mid = 0.5 * (s.dofs[k].lower + s.dofs[k].upper),
                 half = 0.5 * (s.dofs[k].upper - s.dofs[k].lower);
    pose.angles(Eigen::Index(k)) = mid + spread * half * unit(rng);
  }
  return pose;
}

std::vector<Feature> tips(const Skeleton& s) {
  std::vector<Feature> f;
  for (int m : hand::fingertip_markers(s)) f.push_back({m, -1, 1.0});
  return f;
}

// The simulated hand's own pose written as a tracked frame (same morphology and size).
tracking::TrackedHand as_tracked(const Skeleton& s, const HandPose& pose, double hand_length) {
  const hand::BoneFrames frames = hand::forward_kinematics(s, pose);
  hand::LeapJoints j;
  const char* names[5] = {"thumb", "index", "middle", "ring", "pinky"};
  for (int f = 0; f < 5; ++f) {
    const std::string n = names[f];
    const char* joints[5] = {f == 0 ? "_cmc" : "_mcp", f == 0 ? "_cmc" : "_mcp",
                             f == 0 ? "_mcp" : "_pip", f == 0 ? "_ip" : "_dip", "_tip"};
    for (int k = 0; k < 5; ++k)
      j.joints[std::size_t(f)][std::size_t(k)] =
          hand::marker_position(s, frames, s.marker_index(n + joints[k]));
  }
  j.direction = pose.root_rotation.col(1);
  j.palm_normal = pose.root_rotation.col(2);
  j.palm_position =
      pose.root_position + pose.root_rotation * Eigen::Vector3d(0, 0.25 * hand_length, 0);
  j.wrist = pose.root_position;
  return tracking::tracked_hand(j, tracking::Side::kRight);
}

// The KKT conditions at the solution, with the root fixed (five finger blocks) and with the
// wrist free to shift (one block: the translation couples every finger).
class FingertipSolverKkt : public testing::TestWithParam<double> {};

TEST_P(FingertipSolverKkt, HoldAtTheSolution) {
  const double root_weight = GetParam();
  const Skeleton s = hand::build_simulated_hand(hand::HandShape::with_length(0.214));
  SolverOptions options;
  options.spatial_weight = options.temporal_weight = 1e-6;
  options.root_translation_weight = root_weight;
  // Enough for the damping (which does not move the solution) to let the last digits of a fit
  // with a residual converge, linearly.
  options.max_iterations = options.cold_start_iterations = 2000;
  options.step_tolerance = 1e-13;
  options.decrease_tolerance = options.relative_decrease_tolerance = 0.0;
  FingertipSolver solver(s, tips(s), options);
  std::mt19937 rng(5);
  int with_active = 0;
  const int n = int(s.dofs.size());
  for (int trial = 0; trial < 20; ++trial) {
    const HandPose start = random_interior_pose(s, rng);
    // Targets: with the root fixed, the tips of a pose whose angles may lie beyond the limits
    // (by up to 30% of each range), so that some bounds must bind, as a tracked hand beyond
    // the simulated hand's range makes them. With the wrist free, the tips of a pose within
    // the limits with the palm 1 cm off, which the shift must take back: a target out of
    // reach leaves a large residual, where Gauss-Newton's model misses the residual's
    // curvature along the valley that trades palm shift for angles, and converges linearly
    // too slowly for this test's 1e-8 (the retargeter stops on relative decrease there).
    HandPose goal = random_interior_pose(s, rng, root_weight > 0 ? 1.0 : 1.3);
    const hand::BoneFrames frames = hand::forward_kinematics(s, goal);
    std::vector<Eigen::Vector3d> targets;
    for (int m : hand::fingertip_markers(s)) targets.push_back(hand::marker_position(s, frames, m));
    HandPose pose = start;
    pose.root_position = goal.root_position;
    if (root_weight > 0) pose.root_position += Eigen::Vector3d(0.006, -0.008, 0.0);
    pose.root_rotation = goal.root_rotation;
    const SolverResult r = solver.solve(pose, targets);
    Eigen::VectorXd lower(n), upper(n);
    for (int k = 0; k < n; ++k) {
      lower(k) = s.dofs[std::size_t(k)].lower;
      upper(k) = s.dofs[std::size_t(k)].upper;
    }
    const Eigen::VectorXd anchor_clamped = start.angles.cwiseMax(lower).cwiseMin(upper);
    Eigen::VectorXd x = r.angles;
    if (root_weight > 0) {
      x.conservativeResize(n + 3);
      x.tail<3>() = r.root_shift / FingertipSolver::kTranslationUnit;
      EXPECT_GT(r.root_shift.norm(), 1e-4) << "the palm should shift towards the targets";
    }
    const Eigen::VectorXd g = solver.gradient(pose, x, targets, anchor_clamped);
    with_active += !r.active.empty();
    SCOPED_TRACE("iterations " + std::to_string(r.iterations));
    for (int k = 0; k < n; ++k) {
      EXPECT_GE(r.angles(k), lower(k) - 1e-9);
      EXPECT_LE(r.angles(k), upper(k) + 1e-9);
      EXPECT_GE(r.multipliers(k), 0.0) << s.dofs[std::size_t(k)].name;
      // Stationarity: grad f = sum mu grad c, with grad c = +e_k at a lower bound, -e_k at an
      // upper.
      double expected = 0.0;
      if (std::abs(r.angles(k) - lower(k)) < 1e-12 && r.multipliers(k) > 0)
        expected = r.multipliers(k);
      if (std::abs(r.angles(k) - upper(k)) < 1e-12 && r.multipliers(k) > 0)
        expected = -r.multipliers(k);
      EXPECT_NEAR(g(k), expected, 1e-8) << s.dofs[std::size_t(k)].name << " trial " << trial;
    }
    for (int a = n; a < x.size(); ++a)  // the root shift is unbounded
      EXPECT_NEAR(g(a), 0.0, 1e-8) << "root shift " << a - n << " trial " << trial;
  }
  if (root_weight == 0) {
    EXPECT_GT(with_active, 5) << "the test should exercise active bounds";
  }
}

INSTANTIATE_TEST_SUITE_P(RootFixedAndFree, FingertipSolverKkt, testing::Values(0.0, 1e-2));

TEST(Retargeter, OursRecoversTheFingertipsOfTheSameMorphology) {
  const double length = 0.214;
  const Skeleton s = hand::build_simulated_hand(hand::HandShape::with_length(length));
  Retargeter ours(Strategy::kOurs, s, Calibration{});
  std::mt19937 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    const HandPose truth = random_interior_pose(s, rng, 0.6);
    ours.reset();  // unrelated poses: each a new hand, not the next frame of a motion
    const RetargetResult r = ours.retarget(as_tracked(s, truth, length));
    const hand::BoneFrames got = hand::forward_kinematics(s, r.pose);
    const hand::BoneFrames want = hand::forward_kinematics(s, truth);
    for (int m : hand::fingertip_markers(s))
      EXPECT_LT((hand::marker_position(s, got, m) - hand::marker_position(s, want, m)).norm(), 1e-6)
          << "trial " << trial;
  }
}

// Tracked skeletons of 15.9-20.5 cm posed so that thumb and index tips touch.
TEST(Retargeter, SyntheticPinchesStayTouchingWithOurs) {
  const Skeleton sim = hand::build_simulated_hand(hand::HandShape::with_length(0.214));
  for (double length : {0.159, 0.175, 0.19, 0.205}) {
    const Skeleton tracked = hand::build_tracked_hand(hand::HandShape::with_length(length));
    // Pose the tracked hand: flex the fingers, then bring the thumb tip onto the index tip.
    HandPose pose = HandPose::rest(tracked);
    pose.root_rotation = Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    pose.root_position = Eigen::Vector3d(0, 0.15, 0.05);
    for (const char* f : {"index", "middle", "ring", "pinky"}) {
      pose.angles(tracked.dof_index(std::string(f) + "_mcp_flexion")) = 0.5;
      pose.angles(tracked.dof_index(std::string(f) + "_pip_flexion")) = 0.6;
      pose.angles(tracked.dof_index(std::string(f) + "_dip_flexion")) = 0.3;
    }
    const int thumb_tip = tracked.marker_index("thumb_tip"),
              index_tip = tracked.marker_index("index_tip");
    FingertipSolver touch(tracked, {{thumb_tip, index_tip, 1.0}},
                          {1e-9, 1e-9, 0.0, 60, 60, 1e-13, 0.0, 0.0});
    const SolverResult touching = touch.solve(pose, {Eigen::Vector3d::Zero()});
    pose.angles = touching.angles;
    const hand::LeapJoints joints = hand::to_leap_joints(tracked, pose);
    ASSERT_LT((joints.joints[0][4] - joints.joints[1][4]).norm(), 1e-5)
        << "the synthetic pinch must touch, " << length;

    tracking::TrackedHand hand = tracking::tracked_hand(joints, tracking::Side::kRight);
    hand.pinch_strength = 1.0;
    Calibration calibration;
    calibration.scale = 0.214 / length;
    Retargeter ours(Strategy::kOurs, sim, calibration);
    const RetargetResult r = ours.retarget(hand);
    const hand::BoneFrames frames = hand::forward_kinematics(sim, r.pose);
    const double gap = (hand::marker_position(sim, frames, sim.marker_index("thumb_tip")) -
                        hand::marker_position(sim, frames, sim.marker_index("index_tip")))
                           .norm();
    EXPECT_LT(gap, 0.001) << "Ours, tracked hand " << length;

    tracking::TrackedHandFitter fitter(length, tracking::Side::kRight);
    Retargeter naive(Strategy::kNaive, sim, calibration, fitter);
    const RetargetResult n = naive.retarget(hand);
    const hand::BoneFrames nf = hand::forward_kinematics(sim, n.pose);
    const double naive_gap = (hand::marker_position(sim, nf, sim.marker_index("thumb_tip")) -
                              hand::marker_position(sim, nf, sim.marker_index("index_tip")))
                                 .norm();
    std::printf("tracked hand %.1f cm: pinch gap Ours %.3f mm, Naive %.1f mm\n", length * 100,
                gap * 1000, naive_gap * 1000);
  }
}

}  // namespace
}  // namespace handlab::retarget
