#include "core/hand/tracked_hand.h"

#include <cmath>

#include <Eigen/Dense>

#include "core/hand/degrees.h"

namespace handlab::hand {
namespace {

constexpr const char* kJointNames[5] = {"_carp", "_mcp", "_pip", "_dip", "_tip"};
// A fit ends when its step would move no parameter by more than kStepTolerance (rad, or m at
// the root), or when an accepted step lowered the cost by less than kDropTolerance of it.
constexpr double kStepTolerance = 1e-9;
constexpr double kDropTolerance = 1e-8;

}  // namespace

Eigen::Vector3d palm_centre_offset(const HandShape& shape) {
  return Eigen::Vector3d(0, 0.25 * shape.length, 0);
}

Skeleton build_tracked_hand(const HandShape& shape, const MeasuredSkeleton* measured) {
  const double hl = shape.length, hb = shape.hand_breadth();
  const double side = shape.left ? -1.0 : 1.0;
  const Eigen::Matrix3d mirror = Eigen::Vector3d(side, 1, 1).asDiagonal();
  Skeleton s;
  Bone palm;
  palm.name = "palm";
  palm.length = 0.0;
  s.bones.push_back(palm);
  for (int f = 0; f < kFingerCount; ++f) {
    const FingerProportions& p = shape.fingers[std::size_t(f)];
    const std::string name = finger_name(f);
    Eigen::Vector3d mcp(side * p.base_across * hb, p.base_along * hl, 0.0);
    // The metacarpal runs from the carpus, near the wrist and closer to the hand's axis.
    Eigen::Vector3d carp = mcp;
    std::array<double, 3> lengths;
    Eigen::Matrix3d rest;
    if (f == 0) {
      rest = mirror *
             frame_along(Eigen::Vector3d(0.74, 0.66, 0.12), Eigen::Vector3d(-0.2, 0.1, 1.0)) *
             mirror;
      lengths = {p.metacarpal * hl, p.proximal * hl, p.distal * hl};
    } else {
      carp = Eigen::Vector3d(0.45 * mcp.x(), mcp.y() - p.metacarpal * hl * 0.97, 0.0);
      rest = Eigen::Matrix3d::Identity();
      lengths = {p.proximal * hl, p.middle * hl, p.distal * hl};
    }
    if (measured) {
      mcp = measured->mcp[std::size_t(f)];
      carp = f == 0 ? mcp : measured->carp[std::size_t(f)];
      lengths = measured->lengths[std::size_t(f)];
    }
    Bone metacarpal;
    metacarpal.name = name + "_metacarpal";
    metacarpal.parent = 0;
    metacarpal.offset = carp;
    metacarpal.rest =
        frame_along(mcp - carp + Eigen::Vector3d(0, 1e-12, 0), Eigen::Vector3d(side, 0, 0));
    metacarpal.length = (mcp - carp).norm();
    metacarpal.radius = 0.004;
    s.bones.push_back(metacarpal);
    const int metacarpal_index = int(s.bones.size()) - 1;
    int parent = metacarpal_index;
    for (int segment = 0; segment < 3; ++segment) {
      Bone bone;
      static const char* kSegment[3] = {"_proximal", "_intermediate", "_distal"};
      bone.name = name + kSegment[segment];
      bone.parent = parent;
      bone.length = lengths[std::size_t(segment)];
      bone.radius = 0.004;
      if (segment == 0) {
        // The joint sits at the metacarpal's end; its rest frame is the palm's (or the
        // thumb's own), whatever the metacarpal's direction.
        bone.offset = Eigen::Vector3d(0, metacarpal.length, 0);
        bone.rest = metacarpal.rest.transpose() * rest;
      } else {
        bone.offset = Eigen::Vector3d(0, lengths[std::size_t(segment - 1)], 0);
      }
      const Eigen::Vector3d x(1, 0, 0), z(0, 0, 1);
      if (f == 0) {
        if (segment == 0) {
          add_dof(s, bone, name + "_cmc_flexion", x, -20, 55);
          add_dof(s, bone, name + "_cmc_abduction", -side * z, -45, 45);
          add_dof(s, bone, name + "_cmc_rotation", Eigen::Vector3d(0, side, 0), -40, 40);
        } else {
          add_dof(s, bone, name + (segment == 1 ? "_mcp_flexion" : "_ip_flexion"), x, -30, 90);
        }
      } else if (segment == 0) {
        add_dof(s, bone, name + "_mcp_flexion", x, -45, 100);
        add_dof(s, bone, name + "_mcp_abduction", -side * z, -35, 35);
      } else {
        add_dof(s, bone, name + (segment == 1 ? "_pip_flexion" : "_dip_flexion"), x, -20, 120);
      }
      s.bones.push_back(bone);
      parent = int(s.bones.size()) - 1;
    }
    s.markers.push_back({name + kJointNames[0], metacarpal_index, Eigen::Vector3d::Zero()});
    s.markers.push_back({name + kJointNames[1], metacarpal_index + 1, Eigen::Vector3d::Zero()});
    s.markers.push_back({name + kJointNames[2], metacarpal_index + 2, Eigen::Vector3d::Zero()});
    s.markers.push_back({name + kJointNames[3], metacarpal_index + 3, Eigen::Vector3d::Zero()});
    s.markers.push_back(
        {name + kJointNames[4], metacarpal_index + 3, Eigen::Vector3d(0, lengths[2], 0)});
  }
  s.markers.push_back({"palm_centre", 0, palm_centre_offset(shape)});
  return s;
}

LeapJoints to_leap_joints(const Skeleton& tracked, const HandPose& pose) {
  const BoneFrames frames = forward_kinematics(tracked, pose);
  LeapJoints out;
  for (int f = 0; f < kFingerCount; ++f)
    for (int k = 0; k < 5; ++k)
      out.joints[std::size_t(f)][std::size_t(k)] = marker_position(
          tracked, frames, tracked.marker_index(std::string(finger_name(f)) + kJointNames[k]));
  out.palm_position = marker_position(tracked, frames, tracked.marker_index("palm_centre"));
  out.direction = pose.root_rotation.col(1);
  out.palm_normal = pose.root_rotation.col(2);
  out.wrist = pose.root_position;
  return out;
}

FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame, int max_iterations) {
  FitOptions options;
  options.max_iterations = max_iterations;
  return fit_leap_joints(tracked, frame, options);
}

FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          const FitOptions& options) {
  const int max_iterations = options.max_iterations;
  FitResult result;
  HandPose& pose = result.pose;
  if (options.initial) {
    pose = *options.initial;  // the previous frame's fit
  } else {
    // Start from the palm frame the tracker reports.
    pose = HandPose::rest(tracked);
    const Eigen::Vector3d y = frame.direction.normalized();
    const Eigen::Vector3d z = (frame.palm_normal - frame.palm_normal.dot(y) * y).normalized();
    pose.root_rotation.col(0) = y.cross(z);
    pose.root_rotation.col(1) = y;
    pose.root_rotation.col(2) = z;
    const Eigen::Vector3d palm_offset =
        tracked.markers[std::size_t(tracked.marker_index("palm_centre"))].local;
    pose.root_position = frame.palm_position - pose.root_rotation * palm_offset;
  }

  std::vector<std::pair<int, Eigen::Vector3d>> targets;
  std::vector<double> sqrt_weights;
  for (int f = 0; f < kFingerCount; ++f)
    for (int k = 0; k < 5; ++k) {
      const double w = options.weights[std::size_t(5 * f + k)];
      if (w <= 0) continue;
      targets.emplace_back(tracked.marker_index(std::string(finger_name(f)) + kJointNames[k]),
                           frame.joints[std::size_t(f)][std::size_t(k)]);
      sqrt_weights.push_back(std::sqrt(w));
    }
  const int n = tracked.parameter_count();
  const int m = 3 * int(targets.size());
  // Rows weighted by the square root of each joint's weight: the cost is the weighted sum.
  auto residual_of = [&](const BoneFrames& frames, Eigen::VectorXd& r) {
    r.resize(m);
    for (std::size_t t = 0; t < targets.size(); ++t)
      r.segment<3>(Eigen::Index(3 * t)) =
          sqrt_weights[t] *
          (marker_position(tracked, frames, targets[t].first) - targets[t].second);
    return 0.5 * r.squaredNorm();
  };
  auto jacobian_of = [&](const HandPose& p, const BoneFrames& frames, Eigen::MatrixXd& j) {
    j.resize(m, n);
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const int marker = targets[t].first;
      j.middleRows<3>(Eigen::Index(3 * t)) =
          sqrt_weights[t] * point_jacobian(tracked, frames, p,
                                           tracked.markers[std::size_t(marker)].bone,
                                           marker_position(tracked, frames, marker));
    }
  };
  double lambda = 1e-3;
  Eigen::VectorXd r, trial_r;
  Eigen::MatrixXd j, jtj, a;
  Eigen::VectorXd g;
  BoneFrames frames = forward_kinematics(tracked, pose);
  double cost = residual_of(frames, r);
  jacobian_of(pose, frames, j);
  result.iterations = 0;
  for (int it = 0; it < max_iterations; ++it) {
    result.iterations = it + 1;
    jtj.noalias() = j.transpose() * j;
    g.noalias() = j.transpose() * r;
    // Joints held at a limit the descent pushes them through leave the system: the step moves
    // the others, where clamping after a step into the limit would turn it off the descent
    // direction and the fit would crawl along the limit for all its iterations.
    for (std::size_t k = 0; k < tracked.dofs.size(); ++k) {
      const Eigen::Index i = 6 + Eigen::Index(k);
      const double angle = pose.angles(Eigen::Index(k));
      if ((angle <= tracked.dofs[k].lower && g(i) > 0) ||
          (angle >= tracked.dofs[k].upper && g(i) < 0)) {
        jtj.row(i).setZero();
        jtj.col(i).setZero();
        jtj(i, i) = 1.0;
        g(i) = 0.0;
      }
    }
    if (g.norm() < 1e-14) break;
    bool improved = false, converged = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      a = jtj;
      a.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
      const Eigen::VectorXd step = -a.ldlt().solve(g);
      // Converged when the step would move no joint by more than kStepTolerance (rad, or m
      // at the root): far below what a tracker resolves, and where the cost's changes are
      // rounding, which would otherwise spend the remaining iterations and tries.
      if (step.lpNorm<Eigen::Infinity>() < kStepTolerance) {
        converged = true;
        break;
      }
      HandPose trial = pose;
      trial.apply(step);
      trial.clamp_to_limits(tracked);
      const BoneFrames trial_frames = forward_kinematics(tracked, trial);
      const double c2 = residual_of(trial_frames, trial_r);
      if (c2 < cost) {
        // Converged when the cost's relative drop is below kDropTolerance (the joints then
        // move by nanometres); the Jacobian is needed only for a next iteration.
        converged = cost - c2 < kDropTolerance * cost;
        pose = trial;
        frames = trial_frames;
        r.swap(trial_r);
        cost = c2;
        improved = true;
        lambda = std::max(lambda * 0.3, 1e-9);
        if (!converged) jacobian_of(pose, frames, j);
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved || converged) break;
  }
  // Residuals reported unweighted, over the joints that took part.
  double sum = 0.0;
  result.max_residual = 0.0;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const double e = r.segment<3>(Eigen::Index(3 * t)).norm() / sqrt_weights[t];
    sum += e * e;
    result.max_residual = std::max(result.max_residual, e);
  }
  result.rms_residual = std::sqrt(sum / double(std::max<std::size_t>(targets.size(), 1)));
  return result;
}

}  // namespace handlab::hand
