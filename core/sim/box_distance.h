// The analytic distance from a point to a box, for contact against the cube.
#pragma once

#include <Eigen/Core>

namespace handlab::sim {

struct BoxProximity {
  double distance = 0.0;    // signed: negative inside the box
  Eigen::Vector3d closest;  // the nearest point of the box's surface
  Eigen::Vector3d normal;   // the surface's outward normal there (towards the point outside)
};

// In the box's frame: the box [-half, half], the point q.
BoxProximity box_proximity(const Eigen::Vector3d& half, const Eigen::Vector3d& q);

}  // namespace handlab::sim
