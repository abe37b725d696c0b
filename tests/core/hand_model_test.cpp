#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/hand/fit_workspace.h"
#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/hand/tracked_hand.h"
#include "core/mesh/self_intersection.h"

namespace handlab::hand {
namespace {

HandPose random_pose(const Skeleton& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  HandPose pose = HandPose::rest(s);
  pose.root_position = Eigen::Vector3d(0.1, 0.2, -0.05);
  pose.root_rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (std::size_t k = 0; k < s.dofs.size(); ++k)
    pose.angles(Eigen::Index(k)) =
        s.dofs[k].lower + unit(rng) * (s.dofs[k].upper - s.dofs[k].lower);
  return pose;
}

// Central differences of every marker and every bone rotation; the root rotation is
// perturbed in the tangent space, R = exp([phi]x) R0.
TEST(Kinematics, JacobiansMatchCentralDifferences) {
  const Skeleton s = build_simulated_hand(HandShape::with_length(0.214));
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const HandPose pose = random_pose(s, rng);
    const BoneFrames frames = forward_kinematics(s, pose);
    const double h = 1e-6;
    for (int m = 0; m < int(s.markers.size()); ++m) {
      const Eigen::Vector3d p = marker_position(s, frames, m);
      const auto j = point_jacobian(s, frames, pose, s.markers[std::size_t(m)].bone, p);
      for (int c = 0; c < s.parameter_count(); ++c) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(s.parameter_count());
        d(c) = h;
        HandPose plus = pose, minus = pose;
        plus.apply(d);
        minus.apply(-d);
        const Eigen::Vector3d numeric = (marker_position(s, forward_kinematics(s, plus), m) -
                                         marker_position(s, forward_kinematics(s, minus), m)) /
                                        (2 * h);
        const double scale = std::max(1.0, numeric.norm());
        EXPECT_LT((j.col(c) - numeric).norm(), 1e-6 * scale)
            << s.markers[std::size_t(m)].name << " parameter " << c;
      }
    }
    for (int b = 0; b < int(s.bones.size()); ++b) {
      const auto j = rotation_jacobian(s, frames, b);
      for (int c = 0; c < s.parameter_count(); ++c) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(s.parameter_count());
        d(c) = h;
        HandPose plus = pose, minus = pose;
        plus.apply(d);
        minus.apply(-d);
        // dR R^T = [w]x: read w off the skew part.
        const Eigen::Matrix3d dr = (forward_kinematics(s, plus).rotation[std::size_t(b)] -
                                    forward_kinematics(s, minus).rotation[std::size_t(b)]) /
                                   (2 * h) * frames.rotation[std::size_t(b)].transpose();
        const Eigen::Vector3d w(dr(2, 1), dr(0, 2), dr(1, 0));
        EXPECT_LT((j.col(c) - w).norm(), 1e-6 * std::max(1.0, w.norm()))
            << s.bones[std::size_t(b)].name << " " << c;
      }
    }
  }
}

TEST(SimulatedHand, HasSixteenBonesAndAnatomicalDofs) {
  const Skeleton s = build_simulated_hand(HandShape::with_length(0.214));
  EXPECT_EQ(s.bones.size(), 16u);
  EXPECT_EQ(s.dofs.size(), 21u);
  EXPECT_EQ(s.parameter_count(), 27);
  for (const auto& dof : s.dofs) EXPECT_LT(dof.lower, dof.upper) << dof.name;
  // Flexion curls fingers towards the palm (+z), positive abduction is radial (+x).
  HandPose pose = HandPose::rest(s);
  const int tip = s.marker_index("index_tip");
  const Eigen::Vector3d rest_tip = marker_position(s, forward_kinematics(s, pose), tip);
  pose.angles(s.dof_index("index_pip_flexion")) = 1.0;
  EXPECT_GT(marker_position(s, forward_kinematics(s, pose), tip).z(), rest_tip.z() + 0.01);
  pose = HandPose::rest(s);
  pose.angles(s.dof_index("index_mcp_abduction")) = 0.2;
  EXPECT_GT(marker_position(s, forward_kinematics(s, pose), tip).x(), rest_tip.x() + 0.01);
}

class SkinAtSize : public ::testing::TestWithParam<double> {};

TEST_P(SkinAtSize, WatertightManifoldWithoutSelfIntersectionsAndTheRightLength) {
  for (bool left : {false, true}) {
    HandShape shape = HandShape::with_length(GetParam());
    shape.left = left;
    const Skeleton s = build_simulated_hand(shape);
    const HandSkin skin = build_skin(s, shape, 1);
    const auto topology = mesh::surface_topology(skin.surface);
    EXPECT_TRUE(topology.every_edge_shared_by_two);
    EXPECT_TRUE(topology.consistently_oriented);
    EXPECT_EQ(topology.euler_characteristic, 2);
    EXPECT_GT(mesh::enclosed_volume(skin.surface), 0.0);
    EXPECT_TRUE(mesh::self_intersections(skin.surface, 10).empty());
    EXPECT_NEAR(skin.measured_length, shape.length, 0.001);
    // Skinning weights are a partition of unity, and the rest pose reproduces the surface.
    for (Eigen::Index v = 0; v < skin.weights.rows(); ++v)
      EXPECT_NEAR(skin.weights.row(v).sum(), 1.0, 1e-12);
    const auto rest = skin_vertices(s, skin, HandPose::rest(s));
    for (std::size_t v = 0; v < rest.size(); ++v)
      EXPECT_LT((rest[v] - skin.surface.vertices[v]).norm(), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(HandLengths, SkinAtSize,
                         ::testing::Values(0.15, 0.159, 0.175, 0.19, 0.205, 0.214, 0.22));

TEST(Flesh, StudyHandTetsAreValidAndCoupled) {
  const HandShape shape = HandShape::with_length(0.214);
  const Skeleton s = build_simulated_hand(shape);
  const HandFlesh flesh = build_flesh(s, shape);
  const auto& q = flesh.quality;
  EXPECT_GE(q.tets, 2000);
  EXPECT_LE(q.tets, 2800);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_LT(q.max_radius_edge_ratio, 10.0);
  EXPECT_GT(q.min_dihedral_deg, 1.0);
  EXPECT_NEAR(q.total_volume, mesh::enclosed_volume(flesh.skin.surface), 1e-9);
  std::printf("study flesh: %d tets, %zu nodes, radius-edge <= %.2f, min dihedral %.2f deg\n",
              q.tets, flesh.tets.nodes.size(), q.max_radius_edge_ratio, q.min_dihedral_deg);

  // Every bone is coupled; each coupling point lies in its tet and matches its bone point.
  std::vector<double> area(s.bones.size(), 0.0);
  const BoneFrames rest = forward_kinematics(s, HandPose::rest(s));
  for (const auto& c : flesh.coupling) {
    area[std::size_t(c.bone)] += c.area;
    EXPECT_GT(c.barycentric.minCoeff(), -1e-9);
    EXPECT_NEAR(c.barycentric.sum(), 1.0, 1e-12);
    const auto& t = flesh.tets.tets[std::size_t(c.tet)];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k)
      p += c.barycentric[k] * flesh.tets.nodes[std::size_t(t[std::size_t(k)])];
    EXPECT_LT((p - bone_point(rest, c.bone, c.local)).norm(), 1e-9);
  }
  for (std::size_t b = 0; b < s.bones.size(); ++b) EXPECT_GT(area[b], 0.0) << s.bones[b].name;

  // The render surface follows the nodes: at rest it is the finer subdivision of the skin.
  const auto positions = embedded_positions(flesh.render, flesh.tets, flesh.tets.nodes);
  EXPECT_EQ(positions.size(), flesh.render.tet.size());
  EXPECT_GT(positions.size(), flesh.skin.surface.vertices.size());
}

TEST(Flesh, ResolutionScalesTheMesh) {
  const HandShape shape = HandShape::with_length(0.214);
  const Skeleton s = build_simulated_hand(shape);
  FleshOptions four;
  four.resolution = 4;
  const HandFlesh study = build_flesh(s, shape), finer = build_flesh(s, shape, four);
  EXPECT_GT(finer.tets.tets.size(), 3 * study.tets.tets.size());
  EXPECT_GT(finer.quality.min_volume, 0.0);
  EXPECT_THROW(build_flesh(s, shape, {7, 0.0015}), std::invalid_argument);
}

TEST(TrackedHand, LeapMorphology) {
  const Skeleton s = build_tracked_hand(HandShape::with_length(0.18));
  EXPECT_EQ(s.bones.size(), 21u);  // palm + 4 bones x 5 digits
  const LeapJoints joints = to_leap_joints(s, HandPose::rest(s));
  // The thumb's metacarpal has zero length; the fingers' run from near the wrist.
  EXPECT_LT((joints.joints[0][0] - joints.joints[0][1]).norm(), 1e-12);
  for (int f = 1; f < kFingerCount; ++f)
    EXPECT_GT((joints.joints[std::size_t(f)][1] - joints.joints[std::size_t(f)][0]).norm(), 0.04);
  // Middle fingertip to wrist along the hand: its length.
  EXPECT_NEAR(joints.joints[2][4].y(), 0.99 * 0.18, 0.002);
}

TEST(TrackedHand, PoseWrittenAsAFrameFitsBack) {
  std::mt19937 rng(11);
  for (double length : {0.159, 0.18, 0.205}) {
    const Skeleton s = build_tracked_hand(HandShape::with_length(length));
    for (int trial = 0; trial < 4; ++trial) {
      HandPose pose = random_pose(s, rng);
      // Stay away from the limits so that the optimum is interior.
      for (std::size_t k = 0; k < s.dofs.size(); ++k)
        pose.angles(Eigen::Index(k)) =
            0.5 * (s.dofs[k].lower + s.dofs[k].upper) +
            0.6 * (pose.angles(Eigen::Index(k)) - 0.5 * (s.dofs[k].lower + s.dofs[k].upper));
      const LeapJoints frame = to_leap_joints(s, pose);
      const FitResult fit = fit_leap_joints(s, frame);
      const LeapJoints back = to_leap_joints(s, fit.pose);
      for (int f = 0; f < kFingerCount; ++f)
        for (int k = 0; k < 5; ++k)
          EXPECT_LT((back.joints[std::size_t(f)][std::size_t(k)] -
                     frame.joints[std::size_t(f)][std::size_t(k)])
                        .norm(),
                    1e-4)
              << finger_name(f) << " joint " << k << " at " << length;
      EXPECT_LT(fit.max_residual, 1e-4);
    }
  }
}

// A frame whose joints bend past the skeleton's limits (a tracker's hand is not bound by
// ours), fitted from the previous frame's pose as the session does: the fit holds those
// joints at their limits and fits the rest, and gets there in a few iterations rather than
// crawling along the limits for all of them (12 or 13 here, where all 30 were taken before).
TEST(TrackedHand, FrameBeyondTheJointLimitsFitsAtTheLimitsInAFewIterations) {
  std::mt19937 rng(5);
  const Skeleton s = build_tracked_hand(HandShape::with_length(0.18));
  for (int trial = 0; trial < 6; ++trial) {
    HandPose beyond = random_pose(s, rng);
    for (std::size_t k = 0; k < s.dofs.size(); ++k) {
      const double middle = 0.5 * (s.dofs[k].lower + s.dofs[k].upper);
      beyond.angles(Eigen::Index(k)) = middle + 0.6 * (beyond.angles(Eigen::Index(k)) - middle);
    }
    for (std::size_t k = std::size_t(trial % 3); k < s.dofs.size(); k += 3)
      beyond.angles(Eigen::Index(k)) =
          (k / 3) % 2 == 1 ? s.dofs[k].upper + 0.15 : s.dofs[k].lower - 0.15;
    const LeapJoints frame = to_leap_joints(s, beyond);
    HandPose clamped = beyond;
    clamped.clamp_to_limits(s);
    // The previous frame: every joint 0.1 rad inside its range from there, the root 2 mm off.
    HandPose previous = clamped;
    for (std::size_t k = 0; k < s.dofs.size(); ++k) {
      const double middle = 0.5 * (s.dofs[k].lower + s.dofs[k].upper);
      double& angle = previous.angles(Eigen::Index(k));
      angle += std::clamp(middle - angle, -0.1, 0.1);
    }
    previous.root_position += Eigen::Vector3d(0.002, -0.001, 0.001);
    FitOptions options;
    options.initial = &previous;
    const FitResult fit = fit_leap_joints(s, frame, options);
    EXPECT_LE(fit.iterations, 15) << "trial " << trial;  // 30, the limit, without the active set
    // At least as close as the pose clamped to the limits, since that one is allowed.
    const LeapJoints at_limits = to_leap_joints(s, clamped);
    double clamped_sum = 0.0;
    for (int f = 0; f < kFingerCount; ++f)
      for (int k = 0; k < 5; ++k)
        clamped_sum += (at_limits.joints[std::size_t(f)][std::size_t(k)] -
                        frame.joints[std::size_t(f)][std::size_t(k)])
                           .squaredNorm();
    EXPECT_LE(fit.rms_residual, std::sqrt(clamped_sum / 25.0) + 1e-9) << "trial " << trial;
    for (std::size_t k = 0; k < s.dofs.size(); ++k) {
      EXPECT_GE(fit.pose.angles(Eigen::Index(k)), s.dofs[k].lower);
      EXPECT_LE(fit.pose.angles(Eigen::Index(k)), s.dofs[k].upper);
    }
  }
}

// A joint's weight pulls the fit towards it: with the index tip moved 5 mm off the hand and
// weighted 25 times the others, the fitted index tip lies nearer to it than with equal
// weights, and the other joints a little further.
TEST(TrackedHand, AJointsWeightPullsTheFitTowardsIt) {
  std::mt19937 rng(17);
  const Skeleton s = build_tracked_hand(HandShape::with_length(0.18));
  HandPose pose = random_pose(s, rng);
  for (std::size_t k = 0; k < s.dofs.size(); ++k)
    pose.angles(Eigen::Index(k)) = 0.5 * (s.dofs[k].lower + s.dofs[k].upper);
  LeapJoints frame = to_leap_joints(s, pose);
  frame.joints[1][4] += Eigen::Vector3d(0.0, 0.005, 0.0);
  FitOptions weighted;
  weighted.weights[1 * 5 + 4] = 25.0;
  const FitResult equal_fit = fit_leap_joints(s, frame, FitOptions{});
  const FitResult weighted_fit = fit_leap_joints(s, frame, weighted);
  auto tip_error = [&](const FitResult& fit) {
    return (to_leap_joints(s, fit.pose).joints[1][4] - frame.joints[1][4]).norm();
  };
  EXPECT_GT(tip_error(equal_fit), 1e-4);
  EXPECT_LT(tip_error(weighted_fit), 0.5 * tip_error(equal_fit));
  // Residuals are reported unweighted: the others pay for the tip.
  EXPECT_GT(weighted_fit.rms_residual, equal_fit.rms_residual);
}

// A workspace kept from frame to frame (as a tracker's fitter keeps one) gives each frame the
// fit a fresh one gives, bit for bit, whatever the frames before it (other weights, other
// starts); a copy of it fits like a new one; a workspace made for another skeleton is refused.
TEST(TrackedHand, AWorkspaceKeptFromFrameToFrameFitsAsAFreshOne) {
  std::mt19937 rng(23);
  const Skeleton s = build_tracked_hand(HandShape::with_length(0.18));
  FitWorkspace kept(s);
  HandPose previous = HandPose::rest(s);
  for (int frame_index = 0; frame_index < 8; ++frame_index) {
    const LeapJoints frame = to_leap_joints(s, random_pose(s, rng));
    FitOptions options;
    if (frame_index % 2 == 1) options.initial = &previous;
    if (frame_index % 3 == 2)
      for (int d = 0; d < 5; ++d) options.weights[std::size_t(5 * d)] = 0.0;  // no carps
    const FitResult fresh = fit_leap_joints(s, frame, options);
    const FitResult reused = fit_leap_joints(s, frame, options, kept);
    // A copy of a used workspace, and of one never used (whose LDLT has no status yet).
    const FitWorkspace never_used(s);
    FitWorkspace copy = frame_index % 2 == 0 ? kept : never_used;
    const FitResult copied = fit_leap_joints(s, frame, options, copy);
    for (const FitResult* fit : {&reused, &copied}) {
      EXPECT_EQ(fit->iterations, fresh.iterations) << "frame " << frame_index;
      EXPECT_EQ(fit->rms_residual, fresh.rms_residual) << "frame " << frame_index;
      EXPECT_EQ(fit->pose.angles, fresh.pose.angles) << "frame " << frame_index;
      EXPECT_EQ(fit->pose.root_position, fresh.pose.root_position) << "frame " << frame_index;
      EXPECT_EQ(fit->pose.root_rotation, fresh.pose.root_rotation) << "frame " << frame_index;
    }
    previous = fresh.pose;
  }
  Skeleton fewer_markers = s;
  fewer_markers.markers.pop_back();
  EXPECT_THROW(
      fit_leap_joints(fewer_markers, to_leap_joints(s, HandPose::rest(s)), FitOptions{}, kept),
      std::logic_error);
}

}  // namespace
}  // namespace handlab::hand
