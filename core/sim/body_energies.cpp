#include "core/sim/body_energies.h"

#include "core/sim/saturating_damper.h"
#include "core/sim/saturating_spring.h"

namespace handlab::sim {

void add_coupling(const HandSimModel& model, const HandSimState& s, NewtonTerms& terms,
                  const NewtonLayout* layout) {
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const double scale = terms.scale;
  for (std::size_t i = 0; i < model.coupling.size(); ++i) {
    const SimCoupling& c = model.coupling[i];
    const RigidPose& bone = s.bone_pose[std::size_t(c.bone)];
    const Eigen::Vector3d arm = bone.rotation * c.in_bone;
    Eigen::Vector3d flesh_point = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a)
      flesh_point += c.weights(a) * s.node_position[std::size_t(c.nodes[std::size_t(a)])];
    if (!terms.with_hessian) {  // the line search: add_spring's energy alone, as it computes it
      const Eigen::Vector3d d = flesh_point - bone.position - arm;
      terms.energy += 0.5 * d.dot(scale * (c.stiffness * d));
      continue;
    }
    PointJacobian p;
    for (int a = 0; a < 4; ++a) p.add(c.nodes[std::size_t(a)], c.weights(a) * identity);
    p.add_body_point(bone_block(model, c.bone), arm, -1.0);
    terms.add_spring(p, c.stiffness * identity, flesh_point - bone.position - arm,
                     layout && !layout->coupling_blocks.empty()
                         ? layout->coupling_blocks.data() + 36 * i
                         : nullptr);
  }
}

void add_joints(const HandSimModel& model, const HandSimState& s, NewtonTerms& terms,
                const NewtonLayout* layout) {
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (std::size_t i = 0; i < model.joints.size(); ++i) {
    const SimJoint& j = model.joints[i];
    const RigidPose &parent = s.bone_pose[std::size_t(j.parent)],
                    &child = s.bone_pose[std::size_t(j.child)];
    const Eigen::Vector3d arm_p = parent.rotation * j.in_parent,
                          arm_c = child.rotation * j.in_child;
    PointJacobian p;
    p.add_body_point(bone_block(model, j.parent), arm_p, 1.0);
    p.add_body_point(bone_block(model, j.child), arm_c, -1.0);
    terms.add_spring(
        p, model.parameters.joint_stiffness * identity,
        parent.position + arm_p - child.position - arm_c,
        layout && !layout->joint_blocks.empty() ? layout->joint_blocks.data() + 16 * i : nullptr);
  }
}

void add_tracking(const HandSimModel& model, const HandSimState& s,
                  const std::vector<RigidPose>& targets, NewtonTerms& terms) {
  const SimParameters& par = model.parameters;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const double scale = terms.scale;
  for (int b = 0; b < model.bone_count(); ++b) {
    const RigidPose& pose = s.bone_pose[std::size_t(b)];
    const RigidPose& target = targets[std::size_t(b)];
    // Tracking: the centre of mass towards the target's, and the rotation by the rotation
    // vector that separates them (its derivative is the identity near the target).
    const int tb = bone_block(model, b);
    const Eigen::Vector3d phi = rotation_vector(pose.rotation * target.rotation.conjugate());
    const bool finger = model.bones[std::size_t(b)].parent >= 0;
    if (finger && (par.tracking_force_limit > 0 || par.tracking_torque_limit > 0)) {
      const SpringResponse move =
                               saturating_spring(par.tracking_stiffness, par.tracking_force_limit,
                                                 pose.position - target.position),
                           turn = saturating_spring(par.tracking_torsion, par.tracking_torque_limit,
                                                    phi);
      terms.energy += scale * (move.energy + turn.energy);
      terms.gradient.segment<3>(3 * tb) += scale * move.force;
      terms.gradient.segment<3>(3 * (tb + 1)) += scale * turn.force;
      terms.add_block(tb, scale * move.stiffness);
      terms.add_block(tb + 1, scale * turn.stiffness);
      continue;
    }
    PointJacobian centre;
    centre.add(tb, identity);
    terms.add_spring(centre, par.tracking_stiffness * identity, pose.position - target.position);
    terms.energy += 0.5 * scale * par.tracking_torsion * phi.squaredNorm();
    terms.gradient.segment<3>(3 * (tb + 1)) += scale * par.tracking_torsion * phi;
    terms.add_block(tb + 1, scale * par.tracking_torsion * identity);
  }
}

void add_tracking_damping(const HandSimModel& model, const HandSimState& s,
                          const HandSimState& start, NewtonTerms& terms) {
  const SimParameters& par = model.parameters;
  if (par.tracking_damping <= 0) return;
  const double h = par.time_step, scale = terms.scale;
  const double move = par.tracking_damping * par.tracking_stiffness,
               turn = par.tracking_damping * par.tracking_torsion;
  // A turn's saturating speed: the move's at the end of a phalanx (an assumption, about 2 cm).
  const double speed = par.tracking_damping_speed, turn_speed = speed / 0.02;
  for (int b = 0; b < model.bone_count(); ++b) {
    const RigidPose &pose = s.bone_pose[std::size_t(b)], &from = start.bone_pose[std::size_t(b)];
    const int tb = bone_block(model, b);
    const SpringResponse m = saturating_damper(move, speed, h, pose.position - from.position),
                         r = saturating_damper(
                             turn, turn_speed, h,
                             rotation_vector(pose.rotation * from.rotation.conjugate()));
    terms.energy += scale * (m.energy + r.energy);
    terms.gradient.segment<3>(3 * tb) += scale * m.force;
    terms.gradient.segment<3>(3 * (tb + 1)) += scale * r.force;
    terms.add_block(tb, scale * m.stiffness);
    terms.add_block(tb + 1, scale * r.stiffness);
  }
}

void add_gravity(const HandSimModel& model, const HandSimState& s, NewtonTerms& terms) {
  const SimParameters& par = model.parameters;
  const double scale = terms.scale;
  for (int b = 0; b < model.bone_count(); ++b) {
    const double mass = model.bones[std::size_t(b)].inertia.mass;
    terms.energy -= scale * mass * par.gravity.dot(s.bone_pose[std::size_t(b)].position);
    terms.gradient.segment<3>(3 * bone_block(model, b)) -= scale * mass * par.gravity;
  }
  terms.energy -= scale * model.cube.mass * par.gravity.dot(s.cube_pose.position);
  terms.gradient.segment<3>(3 * cube_block(model)) -= scale * model.cube.mass * par.gravity;
  for (int n = 0; n < model.node_count(); ++n) {
    const double mass = model.node_mass[std::size_t(n)];
    if (mass == 0) continue;  // a kinematic point of the cube's substeps: its terms are zero
    terms.energy -= scale * mass * par.gravity.dot(s.node_position[std::size_t(n)]);
    terms.gradient.segment<3>(3 * n) -= scale * mass * par.gravity;
  }
}

void add_kinetic(const HandSimModel& model, const HandSimState& s,
                 const std::vector<Eigen::Vector3d>& turned, const HandSimState& start,
                 NewtonTerms& terms) {
  const double h = model.parameters.time_step;
  for (int n = 0; n < model.node_count(); ++n) {
    const double mass = model.node_mass[std::size_t(n)];
    if (mass == 0) continue;  // as in add_gravity
    const Eigen::Vector3d d = s.node_position[std::size_t(n)] -
                              start.node_position[std::size_t(n)] -
                              h * start.node_velocity[std::size_t(n)];
    terms.energy += 0.5 * mass * d.squaredNorm();
    if (terms.with_hessian) terms.gradient.segment<3>(3 * n) += mass * d;
  }
  auto kinetic = [&](int block, const RigidInertia& inertia, const RigidPose& pose,
                     const RigidPose& from, const RigidVelocity& v,
                     const Eigen::Vector3d& rotated) {
    const Eigen::Vector3d d = pose.position - from.position - h * v.linear;
    terms.energy += 0.5 * inertia.mass * d.squaredNorm();
    terms.gradient.segment<3>(3 * block) += inertia.mass * d;
    terms.add_block(block, inertia.mass * Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d r = from.rotation.toRotationMatrix();
    const Eigen::Matrix3d world = r * inertia.inertia * r.transpose();
    const Eigen::Vector3d a = rotated - h * v.angular;
    terms.energy += 0.5 * a.dot(world * a);
    terms.gradient.segment<3>(3 * (block + 1)) += world * a;
    terms.add_block(block + 1, world);
  };
  for (int b = 0; b < model.bone_count(); ++b)
    kinetic(bone_block(model, b), model.bones[std::size_t(b)].inertia, s.bone_pose[std::size_t(b)],
            start.bone_pose[std::size_t(b)], start.bone_velocity[std::size_t(b)],
            turned[std::size_t(b)]);
  kinetic(cube_block(model), model.cube, s.cube_pose, start.cube_pose, start.cube_velocity,
          turned.back());
}

}  // namespace handlab::sim
