#include <algorithm>
#include <cmath>

#include "core/sim/contact.h"

namespace handlab::sim {
namespace {

// Coulomb's cone on a friction anchor: the friction spring's force k|t| may reach mu f_n, so
// the anchor may be `limit` = mu f_n / k away; beyond, it slides towards the point until it is.
Eigen::Vector3d coulomb_anchor(const Eigen::Vector3d& x, const Eigen::Vector3d& n, double limit,
                               Eigen::Vector3d anchor) {
  const Eigen::Vector3d t = tangent_part(n, x - anchor);
  const double stretch = t.norm();
  if (stretch > limit) anchor += t * (1.0 - limit / stretch);
  return anchor;
}

}  // namespace

// Each contact may switch twice a step and then sticks, so that passes end. Flesh on the cube
// keeps its anchor spring through the step (find_contacts moved its anchor to the cone's edge).
bool friction_changed(const HandSimModel& model, const HandSimState& s,
                      std::vector<Contact>& contacts) {
  bool changed = false;
  for (Contact& c : contacts) {
    if (!c.touching || on_cube(c)) continue;
    if (c.switches >= 2) {
      // A contact that keeps switching ends sticking: the anchor spring is conservative,
      // a kinetic force that disagrees with the motion is not.
      if (c.sliding) {
        c.sliding = false;
        ++c.switches;
        changed = true;
      }
      continue;
    }
    const ContactGap g = contact_gap(model, s, c);
    const double depth = -g.gap;
    if (depth <= 0) continue;  // left the surface: it felt no friction
    const Eigen::Vector3d offset = tangent_part(c.normal, g.x - c.anchor);
    const double limit = friction_cone(model, c, depth);
    const double k = contact_stiffness(model, c);
    if (c.sliding && offset.dot(c.slip) <= 0) {
      // The kinetic force turned the slide back past where the point held: it stops there.
      c.sliding = false;
    } else if (c.sliding && std::abs(k * limit - c.friction_force) > 0.25 * c.friction_force) {
      // Coulomb's force follows the normal force at the result, not at the prediction (a
      // corner predicted deep that bounced out must not take the friction of the depth).
      // Not a switch: the passes' limit ends these updates.
      c.friction_force = k * limit;
      changed = true;
      continue;
    } else if (!c.sliding && offset.norm() > 1.01 * limit) {
      c.sliding = true;
      c.slip = offset.normalized();
      c.friction_force = k * limit;
    } else {
      continue;
    }
    ++c.switches;
    changed = true;
  }
  return changed;
}

double update_anchors(const HandSimModel& model, const std::vector<Contact>& contacts,
                      HandSimState& s) {
  const Eigen::Vector3d nf = model.parameters.floor_normal.normalized();
  s.node_cube.clear();
  s.sample_cube.clear();
  s.node_floor.clear();
  s.corner_floor.clear();
  double max_penetration = 0.0;
  for (const Contact& c : contacts) {
    const ContactGap g = contact_gap(model, s, c);
    if (g.gap >= 0) continue;
    const double depth = -g.gap;
    if (on_cube(c)) {
      max_penetration = std::max(max_penetration, depth);
      (c.kind == Contact::kNodeCube ? s.node_cube : s.sample_cube)
          .push_back({c.point,
                      coulomb_anchor(g.x, g.box.normal, friction_cone(model, c, depth),
                                     c.touching ? c.anchor : g.box.closest),
                      c.face});
      continue;
    }
    (c.kind == Contact::kNodeFloor ? s.node_floor : s.corner_floor)
        .push_back({c.point, coulomb_anchor(g.x, nf, friction_cone(model, c, depth),
                                            c.touching ? c.anchor : g.x - g.gap * nf)});
  }
  return max_penetration;
}

}  // namespace handlab::sim
