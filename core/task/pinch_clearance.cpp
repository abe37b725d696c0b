#include "core/task/pinch_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/sim/box_distance.h"
#include "core/sim/hand_sim_state.h"
#include "core/task/pose_least_squares.h"

namespace handlab::sim {
namespace {

// The penalty aims a little beyond the rule's clearance, which it then meets: at its last
// weight (0.3 doubled seven times, 38.4) it leaves the skin within a micrometre of its aim.
constexpr double kAimedClearance = 0.0022;  // m
constexpr double kFirstWeight = 0.3, kWeightBound = 40.0;
constexpr int kIterations = 300;      // Levenberg-Marquardt's at each weight
constexpr double kDifference = 1e-6;  // the Jacobian's forward differences (m, rad)

// How far q (in the frame of the cube of half sides `half`) lies inside the column under the
// cube widened by `widen` on every side, from its nearer side (> 0; -infinity where q is not
// under the cube's bottom). A point inside the cube keeps its depth below the nearest face, the
// bottom's too: the column's depth starts where the cube's ends.
double column_depth(const Eigen::Vector3d& half, const Eigen::Vector3d& q, double widen) {
  if (q.y() >= -half.y()) return -std::numeric_limits<double>::infinity();
  return std::min(half.x() + widen - std::abs(q.x()), half.z() + widen - std::abs(q.z()));
}

// Whether a ball about `centre` (the cube's frame) of radius `reach` reaches under the cube.
bool reaches_column(const Eigen::Vector3d& half, const Eigen::Vector3d& centre, double reach) {
  return centre.y() - reach < -half.y() && std::abs(centre.x()) < half.x() + reach &&
         std::abs(centre.z()) < half.z() + reach;
}

// A ball about each bone's skin in the bone's frame: the residuals skip a bone whose ball lies
// wholly beyond the penalty's aim (the bones far from the cube, whose points would add zeros).
struct SkinBall {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;  // m, a little over the farthest point's distance (rounding's margin)
};

std::vector<SkinBall> skin_balls(const HandSimModel& model) {
  std::vector<SkinBall> balls(model.bone_skin.size());
  for (std::size_t b = 0; b < balls.size(); ++b) {
    const std::vector<Eigen::Vector3d>& skin = model.bone_skin[b];
    if (skin.empty()) continue;
    Eigen::Vector3d low = skin[0], high = skin[0];
    for (const Eigen::Vector3d& p : skin) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    balls[b].centre = 0.5 * (low + high);
    for (const Eigen::Vector3d& p : skin)
      balls[b].radius = std::max(balls[b].radius, (p - balls[b].centre).norm());
    balls[b].radius = balls[b].radius * (1 + 1e-9) + 1e-12;
  }
  return balls;
}

// Calls visit(bone, &q) for each skin point of every bone but `pads` with the hand at `pose`,
// q the point in the frame of the cube of half sides `half` at `cube`; or visit(bone, nullptr)
// for each point of a bone whose ball (in `balls`, if given) lies wholly farther than `reach`
// outside the cube and its column.
template <class Visit>
void visit_other_skin(const hand::Skeleton& skeleton, const HandSimModel& model,
                      const hand::HandPose& pose, const RigidPose& cube,
                      const Eigen::Vector3d& half, const std::array<int, 2>& pads,
                      const std::vector<SkinBall>* balls, double reach, Visit visit) {
  const std::vector<RigidPose> bones = bone_targets(model, skeleton, pose);
  const Eigen::Quaterniond to_cube = cube.rotation.conjugate();
  const auto in_cube = [&](std::size_t b, const Eigen::Vector3d& local) {
    return Eigen::Vector3d(to_cube * (bones[b].point(local) - cube.position));
  };
  for (std::size_t b = 0; b < bones.size(); ++b) {
    if (int(b) == pads[0] || int(b) == pads[1]) continue;
    const std::vector<Eigen::Vector3d>& skin = model.bone_skin[b];
    const auto far = [&] {
      const Eigen::Vector3d centre = in_cube(b, (*balls)[b].centre);
      const double ball = (*balls)[b].radius + reach;
      return beyond_box(half, centre, ball) && !reaches_column(half, centre, ball);
    };
    if (balls && !skin.empty() && far()) {
      for (std::size_t i = 0; i < skin.size(); ++i) visit(int(b), nullptr);
      continue;
    }
    for (const Eigen::Vector3d& local : skin) {
      const Eigen::Vector3d q = in_cube(b, local);
      visit(int(b), &q);
    }
  }
}

struct Problem {
  const hand::Skeleton& skeleton;
  const HandSimModel& model;
  const std::vector<retarget::Feature>& features;
  const std::vector<Eigen::Vector3d>& goals;
  const RigidPose& cube;
  const std::array<int, 2>& pads;
  double aimed;     // m: the clearance the penalty aims at
  bool free_wrist;  // whether the wrist moves, or the fingers alone
  const PosturePull& pull;
  std::vector<SkinBall> balls = skin_balls(model);

  // The features' weighted misses, then each other skin node's shortfall from the aimed
  // clearance (off the cube and its column) times `weight`, then the pull's.
  Eigen::VectorXd residuals(const hand::HandPose& pose, double weight) const {
    const hand::BoneFrames frames = hand::forward_kinematics(skeleton, pose);
    std::vector<double> r;
    for (std::size_t i = 0; i < features.size(); ++i) {
      const Eigen::Vector3d miss =
          hand::marker_position(skeleton, frames, features[i].marker) - goals[i];
      for (int a = 0; a < 3; ++a) r.push_back(features[i].weight * miss(a));
    }
    // The many points farther than the aim add nothing: told from the axes' gaps alone.
    const Eigen::Vector3d& half = model.cube_half;
    visit_other_skin(
        skeleton, model, pose, cube, half, pads, &balls, aimed, [&](int, const Eigen::Vector3d* q) {
          double shortfall = 0.0;
          if (q) {
            const double column = column_depth(half, *q, aimed);
            const double off =
                beyond_box(half, *q, aimed) ? 0.0 : aimed - box_proximity(half, *q).distance;
            shortfall = std::max({0.0, column, off});
          }
          r.push_back(weight * shortfall);
        });
    for (const int k : pull.dofs) r.push_back(pull.weight * (pose.angles(k) - pull.anchor(k)));
    return Eigen::Map<const Eigen::VectorXd>(r.data(), Eigen::Index(r.size()));
  }

  // Levenberg-Marquardt from `pose` at one weight of the penalty.
  hand::HandPose solve(const hand::HandPose& pose, double weight) const {
    std::vector<int> every_dof(skeleton.dofs.size());
    std::iota(every_dof.begin(), every_dof.end(), 0);
    PoseLeastSquares options;
    options.iterations = kIterations;
    options.difference = kDifference;
    return solve_pose_least_squares(
        pose, (free_wrist ? 6 : 0) + Eigen::Index(skeleton.dofs.size()),
        [&](const hand::HandPose& p) { return residuals(p, weight); },
        [&](const hand::HandPose& p, const Eigen::VectorXd& x) {
          return moved_pose(skeleton, p, every_dof, x, free_wrist);
        },
        options);
  }

  // From `start`, the penalty raised step by step, each step solved from the last.
  hand::HandPose solve_rising(const hand::HandPose& start) const {
    hand::HandPose pose = start;
    for (double weight = kFirstWeight; weight <= kWeightBound; weight *= 2)
      pose = solve(pose, weight);
    return pose;
  }
};

// The nearest skin to the cube, or with `column` to the cube or into the column under it.
SkinClearance nearest_skin(const hand::Skeleton& skeleton, const HandSimModel& model,
                           const hand::HandPose& pose, const RigidPose& cube,
                           const Eigen::Vector3d& half, const std::array<int, 2>& pad_bones,
                           bool column) {
  SkinClearance out;
  out.distance = std::numeric_limits<double>::infinity();
  visit_other_skin(skeleton, model, pose, cube, half, pad_bones, nullptr, 0.0,
                   [&](int bone, const Eigen::Vector3d* q) {
                     const double under = column ? column_depth(half, *q, 0.0) : 0.0;
                     const double d = under > 0 ? -under : box_proximity(half, *q).distance;
                     if (d < out.distance) out = {d, bone};
                   });
  return out;
}

}  // namespace

SkinClearance skin_clearance(const hand::Skeleton& skeleton, const HandSimModel& model,
                             const hand::HandPose& pose, const RigidPose& cube,
                             const Eigen::Vector3d& half, const std::array<int, 2>& pad_bones) {
  return nearest_skin(skeleton, model, pose, cube, half, pad_bones, false);
}

SkinClearance placement_clearance(const hand::Skeleton& skeleton, const HandSimModel& model,
                                  const hand::HandPose& pose, const RigidPose& cube,
                                  const Eigen::Vector3d& half,
                                  const std::array<int, 2>& pad_bones) {
  return nearest_skin(skeleton, model, pose, cube, half, pad_bones, true);
}

ClearPinch clear_pinch(const hand::Skeleton& skeleton, const HandSimModel& model,
                       const std::vector<retarget::Feature>& features,
                       const std::vector<Eigen::Vector3d>& goals, const RigidPose& cube,
                       const std::array<int, 2>& pad_bones, const hand::HandPose& start,
                       const PosturePull& pull) {
  const Problem problem{skeleton,  model,           features, goals, cube,
                        pad_bones, kAimedClearance, true,     pull};
  ClearPinch out;
  out.pose = problem.solve_rising(start);
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton, out.pose);
  for (std::size_t i = 0; i < 2; ++i)
    out.pad_error =
        std::max(out.pad_error,
                 (hand::marker_position(skeleton, frames, features[i].marker) - goals[i]).norm());
  out.clearance = placement_clearance(skeleton, model, out.pose, cube, model.cube_half, pad_bones);
  return out;
}

hand::HandPose clear_descent(const hand::Skeleton& skeleton, const HandSimModel& model,
                             const std::vector<retarget::Feature>& features,
                             const std::vector<Eigen::Vector3d>& goals, const RigidPose& cube,
                             const hand::HandPose& start) {
  const std::array<int, 2> every_bone = {-1, -1};
  const PosturePull none;
  const Problem problem{skeleton,          model, features, goals, cube, every_bone,
                        kDescentClearance, false, none};
  return problem.solve_rising(start);
}

}  // namespace handlab::sim
