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

}  // namespace handlab::render
