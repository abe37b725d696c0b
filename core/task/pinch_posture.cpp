#include "core/task/pinch_posture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/hand/degrees.h"
#include "core/task/pose_least_squares.h"

namespace handlab::sim {
namespace {

constexpr int kPlacementIterations = 500;
constexpr double kPlacementDifference = 1e-7;  // the Jacobian's forward differences (m, rad)

// The posture's angles set, the hand turned and moved so that the first two features lie along
// their goals' axis, their midpoint on their goals'.
hand::HandPose aligned(const hand::Skeleton& skeleton,
                       const std::vector<retarget::Feature>& features,
                       const std::vector<Eigen::Vector3d>& goals, hand::HandPose pose,
                       const Eigen::VectorXd& anchor, const std::vector<int>& dofs) {
  for (const int k : dofs) pose.angles(k) = anchor(k);
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton, pose);
  const Eigen::Vector3d a = hand::marker_position(skeleton, frames, features[0].marker),
                        b = hand::marker_position(skeleton, frames, features[1].marker);
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(a - b, goals[0] - goals[1]).toRotationMatrix();
  pose.root_rotation = turn * pose.root_rotation;
  pose.root_position = turn * (pose.root_position - 0.5 * (a + b)) + 0.5 * (goals[0] + goals[1]);
  return pose;
}

}  // namespace

const char* pinch_posture_name(PinchPosture posture) {
  return posture == PinchPosture::kFunctional ? "functional" : "solved";
}

PinchPosture parse_pinch_posture(const std::string& name) {
  if (name == "solved") return PinchPosture::kSolved;
  if (name == "functional") return PinchPosture::kFunctional;
  throw std::invalid_argument("a pinch's posture is solved or functional, not " + name);
}

const FunctionalPosture& functional_posture() {
  static const FunctionalPosture posture = [] {
    const std::string hume =
        "Hume et al. 1990 (J Hand Surg Am 15(2):240): mean flexion over 11 activities of daily "
        "living, electrogoniometers";
    const std::string fingers = hume + ", the four fingers pooled";
    const std::string middle =
        "assumption: the middle of the model's range (no pinch's value found; docs/simulator.md)";
    FunctionalPosture p;
    p.angles = {{"thumb_cmc_flexion", 17.5 * hand::kDeg, middle},
                {"thumb_cmc_abduction", 10 * hand::kDeg, middle},
                {"thumb_cmc_rotation", 15 * hand::kDeg, middle},
                {"thumb_mcp_flexion", 21 * hand::kDeg, hume},
                {"thumb_ip_flexion", 18 * hand::kDeg, hume},
                {"index_mcp_flexion", 61 * hand::kDeg, fingers},
                {"index_mcp_abduction", 0.0, "assumption: the finger straight on its metacarpal"},
                {"index_pip_flexion", 60 * hand::kDeg, fingers},
                {"index_dip_flexion", 39 * hand::kDeg, fingers}};
    // A radian off the posture weighs as 5 mm of a pad off its goal (assumption): the pads
    // reach their goals within a millimetre, the joints keep off their limits.
    p.weight = 0.005;
    return p;
  }();
  return posture;
}

std::vector<int> posture_dofs(const hand::Skeleton& skeleton) {
  std::vector<int> dofs;
  for (const PostureAngle& a : functional_posture().angles)
    for (std::size_t k = 0; k < skeleton.dofs.size(); ++k)
      if (skeleton.dofs[k].name == a.dof) dofs.push_back(int(k));
  if (dofs.size() != functional_posture().angles.size())
    throw std::invalid_argument("the functional posture needs a thumb and an index");
  return dofs;
}

Eigen::VectorXd posture_anchor(const hand::Skeleton& skeleton, const hand::HandPose& pose) {
  Eigen::VectorXd anchor = pose.angles;
  const std::vector<int> dofs = posture_dofs(skeleton);
  for (std::size_t j = 0; j < dofs.size(); ++j)
    anchor(dofs[j]) = functional_posture().angles[j].angle;
  return anchor;
}

PosturePull functional_pull(const hand::Skeleton& skeleton, const hand::HandPose& pose) {
  return {posture_anchor(skeleton, pose), posture_dofs(skeleton), functional_posture().weight};
}

hand::HandPose place_in_posture(const hand::Skeleton& skeleton,
                                const std::vector<retarget::Feature>& features,
                                const std::vector<Eigen::Vector3d>& goals,
                                const hand::HandPose& start, const PosturePull& pull,
                                bool free_wrist) {
  const Eigen::VectorXd& anchor = pull.anchor;
  const std::vector<int>& dofs = pull.dofs;
  const double weight = pull.weight;
  hand::HandPose pose =
      free_wrist ? aligned(skeleton, features, goals, start, anchor, dofs) : start;
  const Eigen::Matrix3d placed = pose.root_rotation;
  const double wrist_weight = 0.2 * weight;
  auto residuals = [&](const hand::HandPose& p) {
    const hand::BoneFrames frames = hand::forward_kinematics(skeleton, p);
    Eigen::VectorXd r(3 * Eigen::Index(features.size() + 1) + Eigen::Index(dofs.size()));
    Eigen::Index at = 0;
    for (std::size_t i = 0; i < features.size(); ++i, at += 3)
      r.segment<3>(at) = features[i].weight *
                         (hand::marker_position(skeleton, frames, features[i].marker) - goals[i]);
    for (const int k : dofs) r(at++) = weight * (p.angles(k) - anchor(k));
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(p.root_rotation * placed.transpose()));
    r.segment<3>(at) = wrist_weight * turn.angle() * turn.axis();
    return r;
  };
  PoseLeastSquares options;
  options.iterations = kPlacementIterations;
  options.difference = kPlacementDifference;
  options.attempts = 12;
  options.diagonal_floor = 1e-12;
  options.relative_decrease = 1e-12;
  return solve_pose_least_squares(
      pose, (free_wrist ? 6 : 0) + Eigen::Index(dofs.size()), residuals,
      [&](const hand::HandPose& p, const Eigen::VectorXd& x) {
        return moved_pose(skeleton, p, dofs, x, free_wrist);
      },
      options);
}

}  // namespace handlab::sim
