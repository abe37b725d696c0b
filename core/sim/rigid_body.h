// Rigid bodies of the simulator (the hand's bones, the cube): pose, velocity and inertia, and
// the rotation-vector maps that Newton steps on rotations go through.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace handlab::sim {

// A body's frame: its centre of mass and orientation in the world.
struct RigidPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d point(const Eigen::Vector3d& local) const { return position + rotation * local; }
};

struct RigidVelocity {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // of the centre of mass (m/s)
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // world frame (rad/s)
};

// Mass (kg) and the inertia tensor about the centre of mass in the body frame (kg m^2).
struct RigidInertia {
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // centre of mass in the frame it was built in
};

// A solid box of the given edge lengths, centred at the origin.
RigidInertia box_inertia(const Eigen::Vector3d& size, double density);
// A solid capsule: the segment a-b swept by a sphere of `radius`.
RigidInertia capsule_inertia(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
                             double density);
// Several solids as one body (parallel axes), all given in one frame.
RigidInertia combine(const std::vector<RigidInertia>& parts);

// exp: the rotation by the rotation vector v (angle |v| about v / |v|).
Eigen::Quaterniond rotation_from_vector(const Eigen::Vector3d& v);
// log: the rotation vector of q, angle in [0, pi].
Eigen::Vector3d rotation_vector(const Eigen::Quaterniond& q);

// [v]x, the cross-product matrix: [v]x u = v x u.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v);

}  // namespace handlab::sim
