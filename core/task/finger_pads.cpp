#include "core/task/finger_pads.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace handlab::sim {

Eigen::Vector3d finger_pad(const hand::Skeleton& skeleton, const HandSimModel& model, int bone) {
  const hand::BoneFrames rest = hand::forward_kinematics(skeleton, hand::HandPose::rest(skeleton));
  const double length = skeleton.bones[std::size_t(bone)].length;
  double depth = 0.0;  // how far the flesh reaches on the palmar side (+z of the bone frame)
  for (int node : model.surface_nodes) {
    const Eigen::Vector3d local = rest.rotation[std::size_t(bone)].transpose() *
                                  (model.rest[std::size_t(node)] - rest.origin[std::size_t(bone)]);
    // Within the finger's cross-section: the finger is under 2 cm thick.
    if (local.y() < 0.4 * length || local.y() > 0.7 * length || std::abs(local.x()) > 0.004 ||
        std::abs(local.z()) > 0.02)
      continue;
    depth = std::max(depth, local.z());
  }
  if (depth <= 0) throw std::invalid_argument("finger_pad: no flesh on the finger pad");
  return Eigen::Vector3d(0, 0.55 * length, depth);
}

PinchPads pinch_pads(const hand::Skeleton& skeleton, const HandSimModel& model) {
  PinchPads pads;
  pads.thumb_bone = skeleton.bone_index("thumb3");
  pads.index_bone = skeleton.bone_index("index3");
  if (pads.thumb_bone < 0 || pads.index_bone < 0)
    throw std::invalid_argument("pinch_pads: a hand without thumb3 and index3");
  pads.thumb_pad = finger_pad(skeleton, model, pads.thumb_bone);
  pads.index_pad = finger_pad(skeleton, model, pads.index_bone);
  return pads;
}

PadPoints pad_points(const hand::BoneFrames& frames, const PinchPads& pads) {
  return {hand::bone_point(frames, pads.thumb_bone, pads.thumb_pad),
          hand::bone_point(frames, pads.index_bone, pads.index_pad)};
}

}  // namespace handlab::sim
