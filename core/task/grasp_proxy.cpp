#include "core/task/grasp_proxy.h"

#include <algorithm>
#include <stdexcept>

namespace handlab::task {

GraspProxyWorld::GraspProxyWorld(const hand::Skeleton& skeleton, GraspProxySettings settings,
                                 const Eigen::Vector3d& cube_start)
    : skeleton_(skeleton), settings_(settings) {
  thumb_tip_ = skeleton.marker_index("thumb_tip");
  index_tip_ = skeleton.marker_index("index_tip");
  if (thumb_tip_ < 0 || index_tip_ < 0)
    throw std::invalid_argument("the hand needs thumb_tip and index_tip markers");
  thumb_radius_ =
      skeleton.bones[std::size_t(skeleton.markers[std::size_t(thumb_tip_)].bone)].radius;
  index_radius_ =
      skeleton.bones[std::size_t(skeleton.markers[std::size_t(index_tip_)].bone)].radius;
  cube_.position = cube_start;
}

double GraspProxyWorld::distance_to_cube(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d local = cube_.orientation.conjugate() * (point - cube_.position);
  const double half = 0.5 * settings_.cube_size;
  const Eigen::Vector3d outside = (local.cwiseAbs().array() - half).max(0.0).matrix();
  return outside.norm();  // 0 inside
}

void GraspProxyWorld::step(const hand::HandPose* target, double dt) {
  if (!(dt > 0)) throw std::invalid_argument("a step needs dt > 0");
  const Eigen::Vector3d before = cube_.position;
  thumb_contact_ = index_contact_ = false;
  if (target) {
    hand::forward_kinematics(skeleton_, *target, frames_);
    bones_.resize(skeleton_.bones.size());
    for (std::size_t b = 0; b < bones_.size(); ++b) {
      bones_[b].linear() = frames_.rotation[b];
      bones_[b].translation() = frames_.origin[b];
    }
    const Eigen::Vector3d thumb = hand::marker_position(skeleton_, frames_, thumb_tip_);
    const Eigen::Vector3d index = hand::marker_position(skeleton_, frames_, index_tip_);
    const Eigen::Vector3d middle = 0.5 * (thumb + index);
    if (grasped_) {
      cube_.position = middle + grip_offset_;
      // Held, it still cannot pass through the floor (cube-floor contact stays on).
      cube_.position.y() = std::max(cube_.position.y(), 0.5 * settings_.cube_size);
      const double d_thumb = distance_to_cube(thumb), d_index = distance_to_cube(index);
      grasped_ = d_thumb <= thumb_radius_ + settings_.release_margin &&
                 d_index <= index_radius_ + settings_.release_margin;
      thumb_contact_ = index_contact_ = grasped_;
    }
    if (!grasped_) {
      thumb_contact_ = distance_to_cube(thumb) <= thumb_radius_ + settings_.touch_margin;
      index_contact_ = distance_to_cube(index) <= index_radius_ + settings_.touch_margin;
      const bool opposite = (thumb - cube_.position).dot(index - cube_.position) < 0.0;
      if (thumb_contact_ && index_contact_ && opposite) {
        grasped_ = true;
        grip_offset_ = cube_.position - middle;
      }
    }
  } else {
    grasped_ = false;
  }
  if (grasped_) {
    cube_.velocity = (cube_.position - before) / dt;
    return;
  }
  // Free cube: semi-implicit Euler under gravity; the floor stops it dead (no bounce, and
  // friction on the floor holds it once it has landed).
  cube_.velocity.y() -= settings_.gravity * dt;
  cube_.position += dt * cube_.velocity;
  const double half = 0.5 * settings_.cube_size;
  if (cube_.position.y() <= half) {
    cube_.position.y() = half;
    cube_.velocity.setZero();
  }
}

}  // namespace handlab::task
