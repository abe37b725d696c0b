#include "core/tracking/tracked_frame.h"

#include <Eigen/Geometry>

namespace handlab::tracking {

const TrackedHand* TrackedFrame::hand(Side side) const {
  for (const auto& h : hands)
    if (h.side == side) return &h;
  return nullptr;
}

Eigen::Matrix3d palm_frame(const TrackedHand& h) {
  const Eigen::Vector3d y = h.direction.normalized();
  const Eigen::Vector3d z = (h.palm_normal - h.palm_normal.dot(y) * y).normalized();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(z);
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

double thumb_index_distance(const TrackedHand& hand) {
  return (hand.joints[0][4] - hand.joints[1][4]).norm();
}

}  // namespace handlab::tracking
