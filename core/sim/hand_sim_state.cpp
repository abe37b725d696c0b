#include "core/sim/hand_sim_state.h"

namespace handlab::sim {

std::vector<RigidPose> bone_targets(const HandSimModel& model, const hand::Skeleton& skeleton,
                                    const hand::HandPose& pose) {
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton, pose);
  std::vector<RigidPose> out(model.bones.size());
  for (std::size_t b = 0; b < model.bones.size(); ++b) {
    out[b].rotation = Eigen::Quaterniond(frames.rotation[b]).normalized();
    out[b].position = frames.origin[b] + frames.rotation[b] * model.bones[b].centre_in_bone;
  }
  return out;
}

hand::BoneFrames simulated_bone_frames(const HandSimModel& model, const HandSimState& state) {
  hand::BoneFrames frames;
  for (std::size_t b = 0; b < model.bones.size(); ++b) {
    const Eigen::Matrix3d r = state.bone_pose[b].rotation.toRotationMatrix();
    frames.rotation.push_back(r);
    frames.origin.push_back(state.bone_pose[b].position - r * model.bones[b].centre_in_bone);
  }
  return frames;
}

HandSimState initial_state(const HandSimModel& model, const hand::Skeleton& skeleton,
                           const Eigen::Isometry3d& root, const RigidPose& cube) {
  HandSimState s;
  for (const Eigen::Vector3d& x : model.rest) s.node_position.push_back(root * x);
  s.node_velocity.assign(model.rest.size(), Eigen::Vector3d::Zero());
  s.tet_rotation.assign(model.tets.size(), Eigen::Quaterniond(root.linear()).normalized());
  if (!model.bones.empty()) {
    hand::HandPose pose = hand::HandPose::rest(skeleton);
    pose.root_rotation = root.linear();
    pose.root_position = root.translation();
    s.bone_pose = bone_targets(model, skeleton, pose);
  }
  s.bone_velocity.assign(model.bones.size(), RigidVelocity{});
  s.cube_pose = cube;
  return s;
}

Eigen::Vector3d cube_corner(const HandSimModel& model, const RigidPose& pose, int k) {
  const Eigen::Vector3d sign(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
  return pose.point(sign.cwiseProduct(model.cube_half));
}

Eigen::Vector3d skin_sample_position(const HandSimModel& model, const HandSimState& state, int i) {
  const SkinSample& sample = model.skin_samples[std::size_t(i)];
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    x += sample.weights[a] * state.node_position[std::size_t(sample.nodes[std::size_t(a)])];
  return x;
}

}  // namespace handlab::sim
