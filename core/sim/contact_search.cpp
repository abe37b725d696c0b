#include <algorithm>
#include <array>
#include <cmath>

#include "core/sim/contact.h"

namespace handlab::sim {
namespace {

// Points this close to a surface (m), beyond what they can move in a step, are candidates.
constexpr double kContactMargin = 0.001;

}  // namespace

const ContactAnchor* find_anchor(const std::vector<ContactAnchor>& list, int point) {
  const auto it = std::lower_bound(list.begin(), list.end(), point,
                                   [](const ContactAnchor& a, int p) { return a.point < p; });
  return it != list.end() && it->point == point ? &*it : nullptr;
}

Eigen::Vector3d corner_offset(const HandSimModel& model, int k) {
  static const std::array<Eigen::Vector3d, 8> signs = [] {
    std::array<Eigen::Vector3d, 8> s;
    for (int c = 0; c < 8; ++c)
      s[std::size_t(c)] = Eigen::Vector3d(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
    return s;
  }();
  return signs[std::size_t(k)].cwiseProduct(model.cube_half);
}

double contact_stiffness(const HandSimModel& model, const Contact& c) {
  const SimParameters& p = model.parameters;
  if (c.kind == Contact::kCornerFloor) return p.cube_floor_stiffness;
  return on_cube(c) ? model.cube_contact_share * p.contact_stiffness : p.contact_stiffness;
}

double contact_stiffening(const HandSimModel& model, const Contact& c) {
  const SimParameters& p = model.parameters;
  if (c.kind == Contact::kCornerFloor) return p.cube_floor_stiffening;
  return on_cube(c) ? model.cube_contact_share * p.contact_stiffening : p.contact_stiffening;
}

Eigen::Vector3d flesh_point(const HandSimModel& model, const HandSimState& s, const Contact& c) {
  return c.kind == Contact::kSampleCube ? skin_sample_position(model, s, c.point)
                                        : s.node_position[std::size_t(c.point)];
}

PointJacobian flesh_point_jacobian(const HandSimModel& model, const Contact& c) {
  PointJacobian p;
  if (c.kind == Contact::kSampleCube) {
    const SkinSample& sample = model.skin_samples[std::size_t(c.point)];
    for (int a = 0; a < 3; ++a)
      p.add(sample.nodes[std::size_t(a)], sample.weights[a] * Eigen::Matrix3d::Identity());
  } else {
    p.add(c.point, Eigen::Matrix3d::Identity());
  }
  return p;
}

double friction_cone(const HandSimModel& model, const Contact& c, double depth) {
  depth = std::max(depth, 0.0);
  const SimParameters& p = model.parameters;
  return (on_cube(c) ? p.skin_friction : p.friction) * depth *
         (1.0 + contact_stiffening(model, c) * depth / contact_stiffness(model, c));
}

BoxProximity flesh_on_cube(const HandSimModel& model, const Eigen::Vector3d& q, int face) {
  return model.parameters.contact_keeps_face && face >= 0
             ? box_proximity_through(model.cube_half, q, face)
             : box_proximity(model.cube_half, q);
}

ContactGap contact_gap(const HandSimModel& model, const HandSimState& s, const Contact& c) {
  const SimParameters& par = model.parameters;
  ContactGap g;
  if (on_cube(c)) {
    g.x = s.cube_pose.rotation.conjugate() * (flesh_point(model, s, c) - s.cube_pose.position);
    g.box = flesh_on_cube(model, g.x, c.face);
    g.gap = g.box.distance;
    return g;
  }
  g.x = c.kind == Contact::kNodeFloor ? s.node_position[std::size_t(c.point)]
                                      : s.cube_pose.point(corner_offset(model, c.point));
  g.gap = par.floor_normal.normalized().dot(g.x) - par.floor_height;
  return g;
}

void find_contacts(const HandSimModel& model, const HandSimState& s,
                   std::vector<Contact>& contacts) {
  const SimParameters& par = model.parameters;
  const double h = par.time_step;
  contacts.clear();
  const Eigen::Vector3d nf = par.floor_normal.normalized();
  // `x` and `surface` in the surface's frame, `gap` the signed distance.
  auto add = [&](Contact::Kind kind, int point, const Eigen::Vector3d& x, Eigen::Vector3d normal,
                 const Eigen::Vector3d& surface, double gap, const ContactAnchor* old, double k) {
    Contact c{kind, point, normal, old ? old->anchor : surface};
    if (par.contact_keeps_face && on_cube(c)) {
      // The face it came through: kept from the step before, else the one it lies outside of.
      c.face = old && old->face >= 0 ? old->face : box_face(model.cube_half, x);
      const BoxProximity b = box_proximity_through(model.cube_half, x, c.face);
      c.normal = normal = b.normal;
      if (!old) c.anchor = b.closest;
      gap = b.distance;
    }
    c.across = on_cube(c) ? s.cube_pose.rotation * normal : normal;
    c.touching = gap < 0;
    c.curved = c.touching;
    if (c.touching && old) {
      const Eigen::Vector3d t = tangent_part(normal, x - old->anchor);
      const double stretch = t.norm(), limit = friction_cone(model, c, -gap);
      if (stretch > limit) {
        if (on_cube(c)) {
          // Flesh on the cube keeps an anchor spring, its anchor moved to the cone's edge: a
          // constant kinetic force, fixed for the step, set the light cube ringing when a
          // node's slip reversed within it (measured: a soft block resting on the cube).
          c.anchor = old->anchor + t * (1.0 - limit / stretch);
        } else {
          // Sliding: the anchor stays where the point held, in case the slide stops.
          c.sliding = true;
          c.slip = t / stretch;
          c.friction_force = k * limit;
        }
      }
    }
    contacts.push_back(c);
  };
  const double cube_speed =
      s.cube_velocity.linear.norm() + s.cube_velocity.angular.norm() * model.cube_half.norm();
  const Eigen::Quaterniond cube_inv = s.cube_pose.rotation.conjugate();
  for (int node : model.surface_nodes) {
    const Eigen::Vector3d& x = s.node_position[std::size_t(node)];
    const double speed = s.node_velocity[std::size_t(node)].norm();
    const Eigen::Vector3d q = cube_inv * (x - s.cube_pose.position);
    const double reach = kContactMargin + 2 * h * (speed + cube_speed);
    if (!beyond_box(model.cube_half, q, reach)) {
      const BoxProximity b = box_proximity(model.cube_half, q);
      if (b.distance < reach)
        add(Contact::kNodeCube, node, q, b.normal, b.closest, b.distance,
            find_anchor(s.node_cube, node), par.contact_stiffness);
    }
    if (par.hand_floor_contact) {
      const double height = nf.dot(x) - par.floor_height;
      if (height < kContactMargin + 2 * h * speed)
        add(Contact::kNodeFloor, node, x, nf, x - height * nf, height,
            find_anchor(s.node_floor, node), par.contact_stiffness);
    }
  }
  for (int i = 0; i < int(model.skin_samples.size()); ++i) {
    const SkinSample& sample = model.skin_samples[std::size_t(i)];
    const Eigen::Vector3d x = skin_sample_position(model, s, i);
    double squared_speed = 0.0;  // its fastest node's bounds its own
    for (int node : sample.nodes)
      squared_speed = std::max(squared_speed, s.node_velocity[std::size_t(node)].squaredNorm());
    const Eigen::Vector3d q = cube_inv * (x - s.cube_pose.position);
    const double reach = kContactMargin + 2 * h * (std::sqrt(squared_speed) + cube_speed);
    if (beyond_box(model.cube_half, q, reach)) continue;
    const BoxProximity b = box_proximity(model.cube_half, q);
    if (b.distance < reach)
      add(Contact::kSampleCube, i, q, b.normal, b.closest, b.distance,
          find_anchor(s.sample_cube, i), par.contact_stiffness);
  }
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d x = s.cube_pose.point(corner_offset(model, k));
    const double height = nf.dot(x) - par.floor_height;
    if (height < kContactMargin + 2 * h * cube_speed)
      add(Contact::kCornerFloor, k, x, nf, x - height * nf, height, find_anchor(s.corner_floor, k),
          par.cube_floor_stiffness);
  }
}

bool contacts_entered(const HandSimModel& model, const HandSimState& s,
                      std::vector<Contact>& contacts) {
  bool entered = false;
  for (Contact& c : contacts)
    if (!c.curved && contact_gap(model, s, c).gap < 0) c.curved = entered = true;
  return entered;
}

}  // namespace handlab::sim
