#include "core/hand/skeleton.h"

#include <algorithm>
#include <cmath>

#include "core/hand/degrees.h"

namespace handlab::hand {

namespace {
template <typename T>
int index_of(const std::vector<T>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return int(i);
  return -1;
}
}  // namespace

int Skeleton::bone_index(const std::string& name) const {
  return index_of(bones, name);
}
int Skeleton::marker_index(const std::string& name) const {
  return index_of(markers, name);
}
int Skeleton::dof_index(const std::string& name) const {
  return index_of(dofs, name);
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

Eigen::Matrix3d frame_along(const Eigen::Vector3d& direction, const Eigen::Vector3d& x_hint) {
  const Eigen::Vector3d y = direction.normalized();
  const Eigen::Vector3d z = x_hint.cross(y).normalized();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(z);
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

void add_dof(Skeleton& skeleton, Bone& bone, const std::string& name, const Eigen::Vector3d& axis,
             double lower_deg, double upper_deg) {
  if (bone.dof_count == 0) bone.first_dof = int(skeleton.dofs.size());
  skeleton.dofs.push_back({name, axis, lower_deg * kDeg, upper_deg * kDeg});
  ++bone.dof_count;
}

HandPose HandPose::rest(const Skeleton& skeleton) {
  HandPose pose;
  pose.angles = Eigen::VectorXd::Zero(Eigen::Index(skeleton.dofs.size()));
  return pose;
}

void HandPose::apply(const Eigen::VectorXd& delta) {
  root_position += delta.segment<3>(0);
  const Eigen::Vector3d phi = delta.segment<3>(3);
  const double angle = phi.norm();
  if (angle > 0) root_rotation = axis_rotation(phi / angle, angle) * root_rotation;
  // Re-orthonormalise so that many small steps do not drift off SO(3).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(root_rotation,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  root_rotation = svd.matrixU() * svd.matrixV().transpose();
  angles += delta.tail(delta.size() - 6);
}

void HandPose::clamp_to_limits(const Skeleton& skeleton) {
  for (std::size_t k = 0; k < skeleton.dofs.size(); ++k)
    angles(Eigen::Index(k)) =
        std::clamp(angles(Eigen::Index(k)), skeleton.dofs[k].lower, skeleton.dofs[k].upper);
}

BoneFrames forward_kinematics(const Skeleton& skeleton, const HandPose& pose) {
  BoneFrames f;
  forward_kinematics(skeleton, pose, f);
  return f;
}

void forward_kinematics(const Skeleton& skeleton, const HandPose& pose, BoneFrames& f) {
  const std::size_t n = skeleton.bones.size();
  f.rotation.resize(n);
  f.origin.resize(n);
  f.dof_axis.resize(skeleton.dofs.size());
  f.dof_centre.resize(skeleton.dofs.size());
  for (std::size_t b = 0; b < n; ++b) {
    const Bone& bone = skeleton.bones[b];
    const Eigen::Matrix3d& parent_r =
        bone.parent < 0 ? pose.root_rotation : f.rotation[std::size_t(bone.parent)];
    const Eigen::Vector3d& parent_o =
        bone.parent < 0 ? pose.root_position : f.origin[std::size_t(bone.parent)];
    Eigen::Matrix3d r = parent_r * bone.rest;
    const Eigen::Vector3d origin = parent_o + parent_r * bone.offset;
    for (int k = bone.first_dof; k < bone.first_dof + bone.dof_count; ++k) {
      const Dof& dof = skeleton.dofs[std::size_t(k)];
      const Eigen::Vector3d axis = r * dof.axis;
      f.dof_axis[std::size_t(k)] = axis;
      f.dof_centre[std::size_t(k)] = origin;
      // r <- r * rotation(dof.axis, angle), by Rodrigues' formula on r's columns:
      // r (a x e_j) = (r a) x r_j, so column j becomes c r_j + s (ra x r_j) + (1 - c)(ra) a_j.
      const double angle = pose.angles(k), c = std::cos(angle), s = std::sin(angle);
      Eigen::Matrix3d turned;
      for (int j = 0; j < 3; ++j)
        turned.col(j) = c * r.col(j) + s * axis.cross(r.col(j)) + ((1.0 - c) * dof.axis(j)) * axis;
      r = turned;
    }
    f.rotation[b] = r;
    f.origin[b] = origin;
  }
}

Eigen::Vector3d bone_point(const BoneFrames& frames, int bone, const Eigen::Vector3d& local) {
  return frames.origin[std::size_t(bone)] + frames.rotation[std::size_t(bone)] * local;
}

Eigen::Vector3d marker_position(const Skeleton& skeleton, const BoneFrames& frames, int marker) {
  const Marker& m = skeleton.markers[std::size_t(marker)];
  return bone_point(frames, m.bone, m.local);
}

bool in_subtree(const Skeleton& skeleton, int bone, int ancestor) {
  for (int b = bone; b >= 0; b = skeleton.bones[std::size_t(b)].parent)
    if (b == ancestor) return true;
  return false;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> point_jacobian(const Skeleton& skeleton,
                                                        const BoneFrames& frames,
                                                        const HandPose& pose, int bone,
                                                        const Eigen::Vector3d& world) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> j;
  point_jacobian(skeleton, frames, pose, bone, world, j);
  return j;
}

void point_jacobian(const Skeleton& skeleton, const BoneFrames& frames, const HandPose& pose,
                    int bone, const Eigen::Vector3d& world,
                    Eigen::Matrix<double, 3, Eigen::Dynamic>& j) {
  j.setZero(3, skeleton.parameter_count());
  j.leftCols<3>().setIdentity();
  j.middleCols<3>(3) = -skew(world - pose.root_position);  // e_k x r = -[r]x e_k
  for (int b = bone; b >= 0; b = skeleton.bones[std::size_t(b)].parent) {
    const Bone& chain = skeleton.bones[std::size_t(b)];
    for (int k = chain.first_dof; k < chain.first_dof + chain.dof_count; ++k)
      j.col(6 + k) =
          frames.dof_axis[std::size_t(k)].cross(world - frames.dof_centre[std::size_t(k)]);
  }
}

Eigen::Matrix<double, 3, Eigen::Dynamic> rotation_jacobian(const Skeleton& skeleton,
                                                           const BoneFrames& frames, int bone) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> j =
      Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, skeleton.parameter_count());
  j.middleCols<3>(3).setIdentity();
  for (int b = bone; b >= 0; b = skeleton.bones[std::size_t(b)].parent) {
    const Bone& chain = skeleton.bones[std::size_t(b)];
    for (int k = chain.first_dof; k < chain.first_dof + chain.dof_count; ++k)
      j.col(6 + k) = frames.dof_axis[std::size_t(k)];
  }
  return j;
}

}  // namespace handlab::hand
