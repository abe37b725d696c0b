#include "core/retarget/retargeter.h"

#include <algorithm>
#include <stdexcept>

namespace handlab::retarget {
namespace {

constexpr const char* kFingers[5] = {"thumb", "index", "middle", "ring", "pinky"};
constexpr double kRootTranslationWeight = 1e-2;
constexpr double kReachTolerance = 0.0005;  // m: a tip this far off calls for the free wrist

}  // namespace

std::optional<Calibration> calibrate_open_palm(const std::vector<tracking::TrackedFrame>& frames,
                                               tracking::Side side, const hand::Skeleton& simulated,
                                               tracking::TrackedHandFitter fitter) {
  std::vector<double> ratios;
  const hand::Skeleton& tracked = fitter.skeleton();
  for (const auto& f : frames) {
    const tracking::TrackedHand* h = f.hand(side);
    if (!h || h->grab_strength > 0.1) continue;
    // The tracked joints in the palm frame.
    const Eigen::Matrix3d r = tracking::palm_frame(*h);
    Eigen::AlignedBox2d tracked_box;
    for (const auto& digit : h->joints)
      for (int k = 1; k < 5; ++k)
        tracked_box.extend((r.transpose() * (digit[std::size_t(k)] - h->palm_position)).head<2>());
    // The simulated hand in the same pose: the fitted angles copied DOF by DOF.
    const hand::FitResult fit = fitter.fit(*h);
    hand::HandPose pose = hand::HandPose::rest(simulated);
    for (std::size_t k = 0; k < simulated.dofs.size(); ++k) {
      const int source = tracked.dof_index(simulated.dofs[k].name);
      if (source >= 0) pose.angles(Eigen::Index(k)) = fit.pose.angles(source);
    }
    pose.clamp_to_limits(simulated);
    const hand::BoneFrames bones = hand::forward_kinematics(simulated, pose);
    // The same joints as the tracked ones: Leap's thumb "mcp" is the CMC, its "pip" the MCP.
    Eigen::AlignedBox2d simulated_box;
    for (int d = 0; d < 5; ++d) {
      const bool thumb = d == 0;
      for (const char* joint :
           {thumb ? "_cmc" : "_mcp", thumb ? "_mcp" : "_pip", thumb ? "_ip" : "_dip", "_tip"}) {
        const int m = simulated.marker_index(std::string(kFingers[d]) + joint);
        simulated_box.extend(hand::marker_position(simulated, bones, m).head<2>());
      }
    }
    ratios.push_back(simulated_box.diagonal().norm() / tracked_box.diagonal().norm());
  }
  if (ratios.empty()) return std::nullopt;
  std::nth_element(ratios.begin(), ratios.begin() + std::ptrdiff_t(ratios.size() / 2),
                   ratios.end());
  Calibration c;
  c.scale = ratios[ratios.size() / 2];
  return c;
}

Retargeter::Retargeter(Strategy strategy, const hand::Skeleton& simulated, Calibration calibration,
                       std::optional<tracking::TrackedHandFitter> fitter, OursOptions ours)
    : strategy_(strategy),
      simulated_(simulated),
      calibration_(calibration),
      fitter_(std::move(fitter)) {
  for (int f = 1; f < 5; ++f)
    mcp_markers_[std::size_t(f - 1)] = simulated.marker_index(std::string(kFingers[f]) + "_mcp");
  for (int f = 0; f < 5; ++f)
    tip_markers_[std::size_t(f)] = simulated.marker_index(std::string(kFingers[f]) + "_tip");
  const hand::BoneFrames rest =
      hand::forward_kinematics(simulated, hand::HandPose::rest(simulated));
  for (int f = 0; f < 4; ++f)
    mcp_in_palm_[std::size_t(f)] =
        hand::marker_position(simulated, rest, mcp_markers_[std::size_t(f)]);
  if (strategy == Strategy::kNaive && !fitter_)
    throw std::invalid_argument("Naive retargeting needs a tracked-hand fitter");
  std::vector<Feature> features;
  for (int f = 0; f < 5; ++f)
    features.push_back({tip_markers_[std::size_t(f)], -1, ours.tip_weights[std::size_t(f)]});
  SolverOptions options = ours.solver;
  options.root_translation_weight = 0.0;
  solver_ = std::make_unique<FingertipSolver>(simulated, features, options);
  // When a tip stays out of reach from the palm placed on the finger bases (the two
  // skeletons' thumb bases differ), the palm may shift, at a regularised cost.
  options.root_translation_weight = kRootTranslationWeight;
  free_wrist_ = std::make_unique<FingertipSolver>(simulated, features, options);
}

RetargetResult Retargeter::retarget(const tracking::TrackedHand& tracked) {
  const Eigen::Isometry3d& scene = calibration_.tracker_to_scene;
  const double s = calibration_.scale;
  const Eigen::Vector3d centre = tracked.palm_position;
  auto scaled = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return scene * (centre + s * (p - centre));
  };

  RetargetResult out;
  hand::HandPose& pose = out.pose;
  pose = hand::HandPose::rest(simulated_);
  pose.root_rotation = scene.linear() * tracking::palm_frame(tracked);
  // Palms aligned on the four finger bases: the translation that best puts the simulated
  // MCPs on the scaled tracked ones.
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  for (int f = 1; f < 5; ++f)
    shift += scaled(tracked.joints[std::size_t(f)][1]) -
             pose.root_rotation * mcp_in_palm_[std::size_t(f - 1)];
  pose.root_position = shift / 4.0;
  for (int f = 0; f < 5; ++f)
    out.targets[std::size_t(f)] = scaled(tracked.joints[std::size_t(f)][4]);

  if (strategy_ == Strategy::kNaive) {
    // The tracked skeleton's joint angles, copied DOF by DOF (both skeletons name their
    // DOFs alike) and clamped to the simulated hand's limits.
    const hand::FitResult fit = fitter_->fit(tracked);
    const hand::Skeleton& t = fitter_->skeleton();
    for (std::size_t k = 0; k < simulated_.dofs.size(); ++k) {
      const int source = t.dof_index(simulated_.dofs[k].name);
      if (source >= 0) pose.angles(Eigen::Index(k)) = fit.pose.angles(source);
    }
    pose.clamp_to_limits(simulated_);
    out.iterations = fit.iterations;
    return out;
  }
  // Warm start and temporal anchor: the previous frame's solution.
  if (previous_) pose.angles = previous_->angles;
  const std::vector<Eigen::Vector3d> targets(out.targets.begin(), out.targets.end());
  // The palm stays on the finger bases unless a tip is out of reach from there; once it
  // has shifted, it keeps shifting (warm-started) until the shift falls below half the
  // reach tolerance, so that frames do not alternate between the two.
  const bool shifted = previous_ && previous_->root_shift.norm() > 0.5 * kReachTolerance;
  SolverResult solution;
  if (!shifted) {
    solution = solver_->solve(pose, targets, !previous_.has_value());
    out.iterations = solution.iterations;
  }
  if (shifted || solution.max_feature_error > kReachTolerance) {
    // From the fixed palm's solution, or the previous frame's, with its shift.
    if (!shifted) pose.angles = solution.angles;
    solution = free_wrist_->solve(pose, targets, !previous_.has_value(),
                                  previous_ ? previous_->root_shift : Eigen::Vector3d::Zero());
    out.iterations += solution.iterations;
  }
  pose.angles = solution.angles;
  pose.root_position += solution.root_shift;
  previous_ = solution;
  return out;
}

}  // namespace handlab::retarget
