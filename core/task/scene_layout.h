// The physical layout of the pick-and-place task: a floor (y = 0, +y up), start zone A,
// target zone B, and the cube. SI units. The study protocol overrides these defaults.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace handlab::task {

struct SceneLayout {
  Eigen::Vector3d zone_a{-0.15, 0.0, 0.0};  // centre of zone A on the floor (m)
  Eigen::Vector3d zone_b{0.15, 0.0, 0.0};   // centre of zone B on the floor (m)
  double zone_size = 0.10;                  // side of the square target zones (m)
  double cube_size = 0.06;                  // 0.06 gross, 0.01 fine (m)
};

// The cube's resting pose at the centre of zone A.
Eigen::Isometry3d cube_start_pose(const SceneLayout& layout);

}  // namespace handlab::task
