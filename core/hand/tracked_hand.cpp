#include "core/hand/tracked_hand.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "core/hand/degrees.h"
#include "core/hand/fit_workspace.h"

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

std::array<int, 26> leap_joint_markers(const Skeleton& tracked) {
  std::array<int, 26> markers;
  for (int f = 0; f < kFingerCount; ++f)
    for (int k = 0; k < 5; ++k)
      markers[std::size_t(5 * f + k)] =
          tracked.marker_index(std::string(finger_name(f)) + kJointNames[k]);
  markers[25] = tracked.marker_index("palm_centre");
  return markers;
}

LeapJoints to_leap_joints(const Skeleton& tracked, const HandPose& pose) {
  const BoneFrames frames = forward_kinematics(tracked, pose);
  const std::array<int, 26> markers = leap_joint_markers(tracked);
  LeapJoints out;
  for (int f = 0; f < kFingerCount; ++f)
    for (int k = 0; k < 5; ++k)
      out.joints[std::size_t(f)][std::size_t(k)] =
          marker_position(tracked, frames, markers[std::size_t(5 * f + k)]);
  out.palm_position = marker_position(tracked, frames, markers[25]);
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
  FitWorkspace workspace(tracked);
  return fit_leap_joints(tracked, frame, options, workspace);
}

namespace {

// The pose the fit starts from: the previous frame's, or the palm frame the tracker reports.
HandPose initial_pose(const Skeleton& tracked, const LeapJoints& frame, const FitOptions& options,
                      int palm_marker) {
  if (options.initial) return *options.initial;
  HandPose pose = HandPose::rest(tracked);
  const Eigen::Vector3d y = frame.direction.normalized();
  const Eigen::Vector3d z = (frame.palm_normal - frame.palm_normal.dot(y) * y).normalized();
  pose.root_rotation.col(0) = y.cross(z);
  pose.root_rotation.col(1) = y;
  pose.root_rotation.col(2) = z;
  const Eigen::Vector3d palm_offset = tracked.markers[std::size_t(palm_marker)].local;
  pose.root_position = frame.palm_position - pose.root_rotation * palm_offset;
  return pose;
}

// Rows weighted by the square root of each joint's weight: the cost is the weighted sum.
double weighted_residual(const Skeleton& tracked, const FitWorkspace& w, const BoneFrames& frames,
                         Eigen::VectorXd& r) {
  r.resize(Eigen::Index(3 * w.targets.size()));
  for (std::size_t t = 0; t < w.targets.size(); ++t)
    r.segment<3>(Eigen::Index(3 * t)) =
        w.sqrt_weights[t] *
        (marker_position(tracked, frames, w.targets[t].first) - w.targets[t].second);
  return 0.5 * r.squaredNorm();
}

void weighted_jacobian(const Skeleton& tracked, const HandPose& pose, FitWorkspace& w) {
  w.j.resize(Eigen::Index(3 * w.targets.size()), tracked.parameter_count());
  for (std::size_t t = 0; t < w.targets.size(); ++t) {
    const int marker = w.targets[t].first;
    point_jacobian(tracked, w.frames, pose, tracked.markers[std::size_t(marker)].bone,
                   marker_position(tracked, w.frames, marker), w.point_j);
    w.j.middleRows<3>(Eigen::Index(3 * t)) = w.sqrt_weights[t] * w.point_j;
  }
}

// Joints held at a limit the descent pushes them through leave the system: the step moves
// the others, where clamping after a step into the limit would turn it off the descent
// direction and the fit would crawl along the limit for all its iterations.
void hold_joints_at_limits(const Skeleton& tracked, const HandPose& pose, FitWorkspace& w) {
  for (std::size_t k = 0; k < tracked.dofs.size(); ++k) {
    const Eigen::Index i = 6 + Eigen::Index(k);
    const double angle = pose.angles(Eigen::Index(k));
    if ((angle <= tracked.dofs[k].lower && w.g(i) > 0) ||
        (angle >= tracked.dofs[k].upper && w.g(i) < 0)) {
      w.jtj.row(i).setZero();
      w.jtj.col(i).setZero();
      w.jtj(i, i) = 1.0;
      w.g(i) = 0.0;
    }
  }
}

}  // namespace

FitResult fit_leap_joints(const Skeleton& tracked, const LeapJoints& frame,
                          const FitOptions& options, FitWorkspace& w) {
  if (w.marker_count != tracked.markers.size())
    throw std::logic_error("fit_leap_joints: a workspace made for another skeleton");
  FitResult result;
  HandPose& pose = result.pose;
  pose = initial_pose(tracked, frame, options, w.joint_marker[25]);
  w.targets.clear();
  w.sqrt_weights.clear();
  for (std::size_t joint = 0; joint < 25; ++joint) {
    const double weight = options.weights[joint];
    if (weight <= 0) continue;
    w.targets.emplace_back(w.joint_marker[joint], frame.joints[joint / 5][joint % 5]);
    w.sqrt_weights.push_back(std::sqrt(weight));
  }
  double lambda = 1e-3;
  forward_kinematics(tracked, pose, w.frames);
  double cost = weighted_residual(tracked, w, w.frames, w.r);
  weighted_jacobian(tracked, pose, w);
  result.iterations = 0;
  for (int it = 0; it < options.max_iterations; ++it) {
    result.iterations = it + 1;
    w.jtj.noalias() = w.j.transpose() * w.j;
    w.g.noalias() = w.j.transpose() * w.r;
    hold_joints_at_limits(tracked, pose, w);
    if (w.g.norm() < 1e-14) break;
    bool improved = false, converged = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      w.a = w.jtj;
      w.a.diagonal() += lambda * (w.jtj.diagonal().array() + 1e-9).matrix();
      w.ldlt.compute(w.a);
      w.step = w.ldlt.solve(w.g);
      w.step = -w.step;
      // Converged when the step would move no joint by more than kStepTolerance (rad, or m
      // at the root): far below what a tracker resolves, and where the cost's changes are
      // rounding, which would otherwise spend the remaining iterations and tries.
      if (w.step.lpNorm<Eigen::Infinity>() < kStepTolerance) {
        converged = true;
        break;
      }
      w.trial = pose;
      w.trial.apply(w.step);
      w.trial.clamp_to_limits(tracked);
      forward_kinematics(tracked, w.trial, w.trial_frames);
      const double c2 = weighted_residual(tracked, w, w.trial_frames, w.trial_r);
      if (c2 < cost) {
        // Converged when the cost's relative drop is below kDropTolerance (the joints then
        // move by nanometres); the Jacobian is needed only for a next iteration.
        converged = cost - c2 < kDropTolerance * cost;
        pose = w.trial;
        std::swap(w.frames, w.trial_frames);
        w.r.swap(w.trial_r);
        cost = c2;
        improved = true;
        lambda = std::max(lambda * 0.3, 1e-9);
        if (!converged) weighted_jacobian(tracked, pose, w);
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved || converged) break;
  }
  // Residuals reported unweighted, over the joints that took part.
  double sum = 0.0;
  result.max_residual = 0.0;
  for (std::size_t t = 0; t < w.targets.size(); ++t) {
    const double e = w.r.segment<3>(Eigen::Index(3 * t)).norm() / w.sqrt_weights[t];
    sum += e * e;
    result.max_residual = std::max(result.max_residual, e);
  }
  result.rms_residual = std::sqrt(sum / double(std::max<std::size_t>(w.targets.size(), 1)));
  return result;
}

}  // namespace handlab::hand
