#include "core/task/soft_hand_world.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace handlab::task {

SoftHandWorld::SoftHandWorld(const sim::HandSimModel& model, const hand::Skeleton& skeleton,
                             const Eigen::Vector3d& cube_start, sim::SimOptions options)
    : model_(model), skeleton_(skeleton), simulator_(model, options) {
  if (model.bone_count() != int(skeleton.bones.size()))
    throw std::invalid_argument("SoftHandWorld: the model is not of this skeleton's hand");
  const int thumb_tip = skeleton.marker_index("thumb_tip");
  const int index_tip = skeleton.marker_index("index_tip");
  if (thumb_tip < 0 || index_tip < 0)
    throw std::invalid_argument("SoftHandWorld: the hand needs thumb_tip and index_tip markers");
  // A finger is its tip's bone and the ones above it, up to the bone on the root (the palm).
  finger_.assign(skeleton.bones.size(), kOther);
  for (const auto& [tip, finger] : {std::pair{thumb_tip, kThumb}, std::pair{index_tip, kIndex}})
    for (int b = skeleton.markers[std::size_t(tip)].bone;
         b >= 0 && skeleton.bones[std::size_t(b)].parent >= 0;
         b = skeleton.bones[std::size_t(b)].parent)
      finger_[std::size_t(b)] = finger;
  cube_start_.position = cube_start;
  cube_.position = cube_start;
  // Each node belongs to the bone whose capsule surface is nearest at rest (root frame).
  const hand::BoneFrames rest = hand::forward_kinematics(skeleton, hand::HandPose::rest(skeleton));
  node_bone_.assign(std::size_t(model.node_count()), -1);
  for (int n = 0; n < model.node_count(); ++n) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
      const hand::Bone& bone = skeleton.bones[b];
      const Eigen::Vector3d axis = rest.rotation[b].col(1);
      const Eigen::Vector3d from = model.rest[std::size_t(n)] - rest.origin[b];
      const double along = std::clamp(from.dot(axis), 0.0, bone.length);
      const double distance = (from - along * axis).norm() - bone.radius;
      if (distance < nearest) {
        nearest = distance;
        node_bone_[std::size_t(n)] = int(b);
      }
    }
  }
}

void SoftHandWorld::step(const hand::HandPose* target, double dt) {
  if (!(dt > 0)) throw std::invalid_argument("a step needs dt > 0");
  if (target) {
    targets_ = sim::bone_targets(model_, skeleton_, *target);
    if (!state_) {
      Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
      root.linear() = target->root_rotation;
      root.translation() = target->root_position;
      state_ = std::make_unique<sim::HandSimState>(
          sim::initial_state(model_, skeleton_, root, cube_start_));
      pending_ = 0.0;
    }
  }
  if (!state_) return;  // no hand yet: the cube rests where it was put
  const double h = model_.parameters.time_step;
  pending_ += dt;
  while (pending_ > 0.5 * h) {
    const auto start = std::chrono::steady_clock::now();
    const sim::SimStepReport report = simulator_.step(*state_, targets_);
    totals_.add(report,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    pending_ -= h;
  }
  observe();
}

void SoftHandWorld::observe() {
  cube_.position = state_->cube_pose.position;
  cube_.orientation = state_->cube_pose.rotation;
  cube_.velocity = state_->cube_velocity.linear;
  thumb_contact_ = index_contact_ = false;
  auto touches = [&](int node) {
    const int finger = finger_[std::size_t(node_bone_[std::size_t(node)])];
    thumb_contact_ = thumb_contact_ || finger == kThumb;
    index_contact_ = index_contact_ || finger == kIndex;
  };
  for (const sim::ContactAnchor& a : state_->node_cube) touches(a.point);
  // A skin sample belongs to the finger of its face's nearest node.
  for (const sim::ContactAnchor& a : state_->sample_cube) {
    const sim::SkinSample& sample = model_.skin_samples[std::size_t(a.point)];
    Eigen::Index nearest = 0;
    sample.weights.maxCoeff(&nearest);
    touches(sample.nodes[std::size_t(nearest)]);
  }
  const hand::BoneFrames frames = sim::simulated_bone_frames(model_, *state_);
  bones_.resize(frames.origin.size());
  for (std::size_t b = 0; b < bones_.size(); ++b) {
    bones_[b].linear() = frames.rotation[b];
    bones_[b].translation() = frames.origin[b];
  }
}

}  // namespace handlab::task
