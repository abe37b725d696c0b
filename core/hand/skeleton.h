// An articulated skeleton as an immutable model (bones, their rest placement, one-axis
// rotational degrees of freedom with limits, marker points) and a pose (the state: root
// position and rotation, joint angles). Forward kinematics and analytic Jacobians.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace handlab::hand {

struct Dof {
  std::string name;      // "index_mcp_flexion"
  Eigen::Vector3d axis;  // unit axis in the bone's frame before this DOF's rotation
  double lower, upper;   // limits (rad)
};

struct Bone {
  std::string name;
  int parent = -1;                                     // -1: attached to the root (wrist) frame
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();    // joint centre in the parent's frame
  Eigen::Matrix3d rest = Eigen::Matrix3d::Identity();  // rest orientation relative to parent
  double length = 0.0;                                 // along the bone's +y
  double radius = 0.0;                                 // of its capsule
  int first_dof = 0, dof_count = 0;                    // DOFs applied in order after `rest`
};

// A point fixed to a bone (a joint centre, a fingertip): position in the bone's frame.
struct Marker {
  std::string name;
  int bone;
  Eigen::Vector3d local;
};

struct Skeleton {
  std::vector<Bone> bones;  // parents before children
  std::vector<Dof> dofs;
  std::vector<Marker> markers;

  int bone_index(const std::string& name) const;    // -1 when absent
  int marker_index(const std::string& name) const;  // -1 when absent
  int dof_index(const std::string& name) const;     // -1 when absent
  // Pose parameters: 3 root translation, 3 root rotation (tangent space), then the DOFs.
  int parameter_count() const { return 6 + int(dofs.size()); }
};

struct HandPose {
  Eigen::Vector3d root_position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d root_rotation = Eigen::Matrix3d::Identity();
  Eigen::VectorXd angles;  // one per DOF

  static HandPose rest(const Skeleton& skeleton);
  // Applies a step in pose parameters: position += d[0..3], rotation = exp([d[3..6]]x) R,
  // angles += d[6..].
  void apply(const Eigen::VectorXd& delta);
  // Joint angles clamped to their limits.
  void clamp_to_limits(const Skeleton& skeleton);
};

// World frames of every bone for a pose.
struct BoneFrames {
  std::vector<Eigen::Matrix3d> rotation;
  std::vector<Eigen::Vector3d> origin;
  // World axis and centre of every DOF, for Jacobians.
  std::vector<Eigen::Vector3d> dof_axis;
  std::vector<Eigen::Vector3d> dof_centre;
};

BoneFrames forward_kinematics(const Skeleton& skeleton, const HandPose& pose);
// The same into `frames`, reusing its storage (no allocation once it has the right sizes).
void forward_kinematics(const Skeleton& skeleton, const HandPose& pose, BoneFrames& frames);

Eigen::Vector3d marker_position(const Skeleton& skeleton, const BoneFrames& frames, int marker);
Eigen::Vector3d bone_point(const BoneFrames& frames, int bone, const Eigen::Vector3d& local);

// d(point)/d(pose parameters), 3 x parameter_count, for a point fixed to `bone` at world
// position `world`. Root rotation columns follow R = (I + [phi]x) R0: column k is e_k x (p - root).
Eigen::Matrix<double, 3, Eigen::Dynamic> point_jacobian(const Skeleton& skeleton,
                                                        const BoneFrames& frames,
                                                        const HandPose& pose, int bone,
                                                        const Eigen::Vector3d& world);
// The same into `j`, reusing its storage (no allocation once it is 3 x parameter_count).
void point_jacobian(const Skeleton& skeleton, const BoneFrames& frames, const HandPose& pose,
                    int bone, const Eigen::Vector3d& world,
                    Eigen::Matrix<double, 3, Eigen::Dynamic>& j);
// Angular velocity of `bone`'s frame per pose parameter, 3 x parameter_count: the
// rotation's Jacobian in the tangent space, dR = [w]x R.
Eigen::Matrix<double, 3, Eigen::Dynamic> rotation_jacobian(const Skeleton& skeleton,
                                                           const BoneFrames& frames, int bone);

// Is `bone` the same as or a descendant of `ancestor`?
bool in_subtree(const Skeleton& skeleton, int bone, int ancestor);

Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& axis, double angle);
// Orientation whose +y points along `direction` and whose +x is as close as possible to `x_hint`.
Eigen::Matrix3d frame_along(const Eigen::Vector3d& direction, const Eigen::Vector3d& x_hint);
// Appends a DOF (limits in degrees) to `bone`, which must be the last bone being built.
void add_dof(Skeleton& skeleton, Bone& bone, const std::string& name, const Eigen::Vector3d& axis,
             double lower_deg, double upper_deg);
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

}  // namespace handlab::hand
