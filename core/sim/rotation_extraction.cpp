#include "core/sim/rotation_extraction.h"

#include <cmath>

#include <Eigen/SVD>

namespace handlab::sim {

void extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations) {
  for (int i = 0; i < max_iterations; ++i) {
    const Eigen::Matrix3d r = q.toRotationMatrix();
    // The torque that turns R's columns towards F's, over their alignment.
    const Eigen::Vector3d omega =
        (r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2))) /
        (std::abs(r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2))) + 1e-9);
    const double w = omega.norm();
    if (w < 1e-12) return;
    q = Eigen::Quaterniond(Eigen::AngleAxisd(w, omega / w)) * q;
    q.normalize();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) = -u.col(2);
  q = Eigen::Quaterniond(u * svd.matrixV().transpose());
  q.normalize();
}

}  // namespace handlab::sim
