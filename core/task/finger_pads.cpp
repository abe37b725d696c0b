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

}  // namespace handlab::sim
