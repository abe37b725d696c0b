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
// Whether q lies farther than `reach` (> 0) outside the box, told from the axes' gaps alone
// (each no more than the distance) for the many far points, before box_proximity's norm: true
// only where box_proximity's distance is at least `reach` too.
bool beyond_box(const Eigen::Vector3d& half, const Eigen::Vector3d& q, double reach);

// The box's faces are numbered 2 axis + (1 on the positive side, 0 on the negative).
// The face whose plane q lies farthest outside of (inside the box: the nearest face).
int box_face(const Eigen::Vector3d& half, const Eigen::Vector3d& q);
// As box_proximity, but a point inside is pushed out through `face`: its depth is below that
// face's plane, however near another face it lies.
BoxProximity box_proximity_through(const Eigen::Vector3d& half, const Eigen::Vector3d& q, int face);

}  // namespace handlab::sim
