// Draw items for hands: a skin surface shaded smooth, and skeletons as capsules.
#pragma once

#include <Eigen/Geometry>

#include "core/hand/skeleton.h"
#include "core/render/draw_list.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::render {

// `placement` moves the hand's frame into the scene.
void draw_skin(DrawList& list, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles, const Eigen::Isometry3d& placement,
               const Eigen::Vector4f& color);
// Each bone as a capsule from its joint to its end, and each marker as a small sphere.
void draw_skeleton(DrawList& list, const hand::Skeleton& skeleton, const hand::HandPose& pose,
                   const Eigen::Isometry3d& placement, const Eigen::Vector4f& bone_color,
                   const Eigen::Vector4f& joint_color, double radius_scale = 1.0);

// A hand's bone capsules, made once per hand and shared by every frame drawn of it (the
// renderer uploads a mesh once per address).
struct BoneMeshes {
  std::vector<std::shared_ptr<const RenderMesh>> capsules;  // per bone; null: zero length
};
BoneMeshes make_bone_meshes(const hand::Skeleton& skeleton);
// A hand whose bones are placed by world frames (a simulation's state, a stored frame):
// each bone's capsule from its frame's origin along its length.
void draw_bone_frames(DrawList& list, const BoneMeshes& meshes,
                      const std::vector<Eigen::Isometry3d>& frames, const Eigen::Vector4f& color);
// A tracked (Leap) hand as it arrives: a capsule between consecutive joints of every digit
// and across the knuckles, moved into the scene by `placement`.
void draw_tracked_hand(DrawList& list, const tracking::TrackedHand& hand,
                       const Eigen::Isometry3d& placement, const Eigen::Vector4f& color);

}  // namespace handlab::render
