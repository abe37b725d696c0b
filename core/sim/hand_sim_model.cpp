#include "core/sim/hand_sim_model.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

namespace handlab::sim {

std::vector<std::array<int, 3>> boundary_faces(const std::vector<std::array<int, 4>>& tets) {
  std::map<std::array<int, 3>, int> faces;
  for (const auto& t : tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      int k = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[std::size_t(k++)] = t[std::size_t(a)];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  std::vector<std::array<int, 3>> out;
  for (const auto& [f, count] : faces)
    if (count == 1) out.push_back(f);
  return out;
}

std::vector<int> boundary_nodes(const std::vector<std::array<int, 4>>& tets, int node_count) {
  std::vector<bool> on(std::size_t(node_count), false);
  for (const auto& f : boundary_faces(tets))
    for (int n : f) on[std::size_t(n)] = true;
  std::vector<int> out;
  for (int n = 0; n < node_count; ++n)
    if (on[std::size_t(n)]) out.push_back(n);
  return out;
}

namespace {

void add_cube(HandSimModel& m) {
  const SimParameters& p = m.parameters;
  if (!(p.cube_size > 0) || !(p.cube_density > 0))
    throw std::invalid_argument("the cube needs a positive size and density");
  m.cube = box_inertia(Eigen::Vector3d::Constant(p.cube_size), p.cube_density);
  m.cube_half = Eigen::Vector3d::Constant(p.cube_size / 2);
}

// A sample at each boundary face's centroid.
void add_skin_samples(HandSimModel& m, const std::vector<std::array<int, 3>>& faces) {
  const int per_face = m.parameters.skin_samples;
  if (per_face != 0 && per_face != 1)
    throw std::invalid_argument("skin samples per face must be 0 or 1");
  if (per_face == 1)
    for (const auto& f : faces) m.skin_samples.push_back({f, Eigen::Vector3d::Constant(1.0 / 3)});
  const double points = double(m.surface_nodes.size() + m.skin_samples.size());
  m.cube_contact_share = points > 0 ? double(m.surface_nodes.size()) / points : 1.0;
}

// Each surface node to the bone whose capsule's surface is nearest it at rest.
void add_bone_skin(HandSimModel& m, const hand::Skeleton& skeleton, const hand::HandFlesh& flesh) {
  const hand::BoneFrames rest = hand::forward_kinematics(skeleton, hand::HandPose::rest(skeleton));
  m.bone_skin.assign(m.bones.size(), {});
  m.node_bone.assign(m.rest.size(), -1);
  for (int n : m.surface_nodes) {
    const Eigen::Vector3d& x = m.rest[std::size_t(n)];
    double nearest = std::numeric_limits<double>::infinity();
    int bone = 0;
    for (const hand::Capsule& c : flesh.capsules) {
      const std::size_t b = std::size_t(c.bone);
      const Eigen::Vector3d a = rest.origin[b] + rest.rotation[b] * c.a;
      const Eigen::Vector3d ab = rest.rotation[b] * (c.b - c.a);
      const double t = std::clamp((x - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
      const double d = (x - a - t * ab).norm() - c.radius;
      if (d < nearest) nearest = d, bone = c.bone;
    }
    const std::size_t b = std::size_t(bone);
    m.node_bone[std::size_t(n)] = bone;
    m.bone_skin[b].push_back(rest.rotation[b].transpose() * (x - rest.origin[b]) -
                             m.bones[b].centre_in_bone);
  }
}

}  // namespace

HandSimModel make_cube_sim_model(const SimParameters& parameters) {
  HandSimModel m;
  m.parameters = parameters;
  add_cube(m);
  return m;
}

HandSimModel make_soft_body_sim_model(const mesh::TetMesh& mesh, const SimParameters& parameters) {
  HandSimModel m = make_cube_sim_model(parameters);
  const SimParameters& p = m.parameters;
  m.rest = mesh.nodes;
  m.node_mass.assign(m.rest.size(), 0.0);
  for (const auto& ids : mesh.tets) {
    const std::array<Eigen::Vector3d, 4> x = {
        m.rest[std::size_t(ids[0])], m.rest[std::size_t(ids[1])], m.rest[std::size_t(ids[2])],
        m.rest[std::size_t(ids[3])]};
    m.tets.push_back(make_tet_element(x, ids));
    for (int id : ids) m.node_mass[std::size_t(id)] += p.flesh_density * m.tets.back().volume / 4;
  }
  m.surface_nodes = boundary_nodes(mesh.tets, int(m.rest.size()));
  add_skin_samples(m, boundary_faces(mesh.tets));
  return m;
}

HandSimModel make_hand_sim_model(const hand::Skeleton& skeleton, const hand::HandFlesh& flesh,
                                 const SimParameters& parameters) {
  HandSimModel m = make_soft_body_sim_model(flesh.tets, parameters);
  const SimParameters& p = m.parameters;
  // Bones: mass and inertia of their capsules (the palm has one per metacarpal).
  std::vector<std::vector<RigidInertia>> parts(skeleton.bones.size());
  for (const hand::Capsule& c : flesh.capsules)
    parts[std::size_t(c.bone)].push_back(capsule_inertia(c.a, c.b, c.radius, p.bone_density));
  for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
    if (parts[b].empty()) throw std::invalid_argument("a bone without a capsule");
    SimBone bone;
    bone.parent = skeleton.bones[b].parent;
    bone.inertia = combine(parts[b]);
    bone.centre_in_bone = bone.inertia.centre;
    m.bones.push_back(bone);
  }
  // Joints: the child's origin (its joint centre) seen from both centres of mass.
  for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
    const hand::Bone& bone = skeleton.bones[b];
    if (bone.parent < 0) continue;
    SimJoint j;
    j.parent = bone.parent;
    j.child = int(b);
    j.in_parent = bone.offset - m.bones[std::size_t(bone.parent)].centre_in_bone;
    j.in_child = -m.bones[b].centre_in_bone;
    m.joints.push_back(j);
  }
  // Coupling springs, their stiffness in proportion to the bone surface they stand for.
  for (const hand::CouplingPoint& c : flesh.coupling) {
    SimCoupling s;
    s.bone = c.bone;
    s.nodes = flesh.tets.tets[std::size_t(c.tet)];
    s.weights = c.barycentric;
    s.in_bone = c.local - m.bones[std::size_t(c.bone)].centre_in_bone;
    s.stiffness = p.coupling_stiffness * c.area;
    m.coupling.push_back(s);
  }
  add_bone_skin(m, skeleton, flesh);
  return m;
}

}  // namespace handlab::sim
