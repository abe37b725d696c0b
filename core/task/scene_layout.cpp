#include "core/task/scene_layout.h"

namespace handlab::task {

Eigen::Isometry3d cube_start_pose(const SceneLayout& layout) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = layout.zone_a + Eigen::Vector3d(0.0, 0.5 * layout.cube_size, 0.0);
  return pose;
}

}  // namespace handlab::task
