#include "core/render/hand_drawing.h"

namespace handlab::render {

void draw_skin(DrawList& list, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles, const Eigen::Isometry3d& placement,
               const Eigen::Vector4f& color) {
  std::vector<Eigen::Vector3f> positions;
  positions.reserve(vertices.size());
  for (const auto& v : vertices) positions.push_back((placement * v).cast<float>());
  DrawItem item;
  item.mesh = std::make_shared<const RenderMesh>(make_smooth_mesh(positions, triangles));
  item.color = color;
  item.dynamic = true;
  list.items.push_back(item);
}

void draw_skeleton(DrawList& list, const hand::Skeleton& skeleton, const hand::HandPose& pose,
                   const Eigen::Isometry3d& placement, const Eigen::Vector4f& bone_color,
                   const Eigen::Vector4f& joint_color, double radius_scale) {
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton, pose);
  for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
    const hand::Bone& bone = skeleton.bones[b];
    if (bone.length <= 0) continue;
    const float radius = float(bone.radius * radius_scale);
    DrawItem item;
    item.mesh = std::make_shared<const RenderMesh>(make_capsule_mesh(radius, float(bone.length)));
    Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
    frame.linear() = frames.rotation[b];
    frame.translation() = frames.origin[b];
    item.model = (placement * frame).matrix().cast<float>();
    item.color = bone_color;
    list.items.push_back(item);
  }
  const auto sphere = std::make_shared<const RenderMesh>(make_capsule_mesh(1.0f, 0.0f, 12));
  for (std::size_t m = 0; m < skeleton.markers.size(); ++m) {
    const hand::Bone& bone = skeleton.bones[std::size_t(skeleton.markers[m].bone)];
    const double r = 1.25 * std::max(bone.radius, 0.004) * radius_scale;
    Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
    model.block<3, 3>(0, 0) = Eigen::Matrix3f::Identity() * float(r);
    model.block<3, 1>(0, 3) =
        (placement * hand::marker_position(skeleton, frames, int(m))).cast<float>();
    list.items.push_back({sphere, model, joint_color, Shading::kLit});
  }
}

BoneMeshes make_bone_meshes(const hand::Skeleton& skeleton) {
  BoneMeshes meshes;
  for (const hand::Bone& bone : skeleton.bones)
    meshes.capsules.push_back(bone.length > 0
                                  ? std::make_shared<const RenderMesh>(
                                        make_capsule_mesh(float(bone.radius), float(bone.length)))
                                  : nullptr);
  return meshes;
}

void draw_bone_frames(DrawList& list, const BoneMeshes& meshes,
                      const std::vector<Eigen::Isometry3d>& frames, const Eigen::Vector4f& color) {
  for (std::size_t b = 0; b < meshes.capsules.size() && b < frames.size(); ++b) {
    if (!meshes.capsules[b]) continue;
    DrawItem item;
    item.mesh = meshes.capsules[b];
    item.model = frames[b].matrix().cast<float>();
    item.color = color;
    list.items.push_back(item);
  }
}

void draw_tracked_hand(DrawList& list, const tracking::TrackedHand& hand,
                       const Eigen::Isometry3d& placement, const Eigen::Vector4f& color) {
  constexpr float kRadius = 0.0045f;
  auto segment = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d pa = placement * a, pb = placement * b;
    const double length = (pb - pa).norm();
    if (length < 1e-6) return;
    // The capsule mesh runs along its frame's +y (make_capsule_mesh).
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), (pb - pa) / length);
    Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
    frame.linear() = turn.toRotationMatrix();
    frame.translation() = pa;
    DrawItem item;
    item.mesh = std::make_shared<const RenderMesh>(make_capsule_mesh(kRadius, float(length), 10));
    item.model = frame.matrix().cast<float>();
    item.color = color;
    list.items.push_back(item);
  };
  for (const auto& digit : hand.joints)
    for (int k = 0; k < 4; ++k) segment(digit[std::size_t(k)], digit[std::size_t(k + 1)]);
  for (int d = 0; d < 4; ++d)
    segment(hand.joints[std::size_t(d)][1], hand.joints[std::size_t(d + 1)][1]);
  segment(hand.wrist, hand.joints[4][0]);
}

}  // namespace handlab::render
