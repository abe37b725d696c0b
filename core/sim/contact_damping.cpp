#include "core/sim/contact_damping.h"

#include <algorithm>
#include <stdexcept>

namespace handlab::sim {

void set_contact_dampers(const HandSimModel& model, const HandSimState& start,
                         const std::vector<Contact>& contacts,
                         std::vector<ContactDamper>& dampers) {
  const Eigen::Quaterniond to_cube = start.cube_pose.rotation.conjugate();
  dampers.assign(contacts.size(), ContactDamper{});
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (!on_cube(c)) continue;
    ContactDamper& d = dampers[i];
    d.rest = to_cube * (flesh_point(model, start, c) - start.cube_pose.position);
    const double depth = std::max(0.0, -flesh_on_cube(model, d.rest, c.face).distance);
    d.force = depth * (contact_stiffness(model, c) + contact_stiffening(model, c) * depth);
  }
}

void add_contact_damping(const HandSimModel& model, const HandSimState& s,
                         const std::vector<Contact>& contacts,
                         const std::vector<ContactDamper>& dampers, NewtonTerms& terms) {
  if (dampers.size() != contacts.size())
    throw std::logic_error("add_contact_damping: a damper a contact (set_contact_dampers)");
  const double per_h = model.parameters.contact_damping / model.parameters.time_step;
  const int cube = cube_block(model);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (!on_cube(c) || !c.touching || dampers[i].force <= 0) continue;
    const Eigen::Vector3d x = flesh_point(model, s, c);
    const BoxProximity b =
        flesh_on_cube(model, s.cube_pose.rotation.conjugate() * (x - s.cube_pose.position), c.face);
    if (b.distance >= 0) continue;  // no pull from a point that left
    PointJacobian damper = flesh_point_jacobian(model, c);
    const Eigen::Vector3d rest = s.cube_pose.point(dampers[i].rest);
    damper.add_body_point(cube, rest - s.cube_pose.position, -1.0);
    terms.add_spring(damper, per_h * dampers[i].force * c.across * c.across.transpose(), x - rest);
  }
}

}  // namespace handlab::sim
