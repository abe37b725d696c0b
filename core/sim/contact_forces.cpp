#include "core/sim/contact_forces.h"

#include "core/sim/contact.h"

namespace handlab::sim {

std::array<double, 6> flesh_forces_on_cube_faces(const HandSimModel& model,
                                                 const HandSimState& state) {
  std::array<double, 6> faces{};
  auto add = [&](Contact::Kind kind, const std::vector<ContactAnchor>& anchors) {
    for (const ContactAnchor& a : anchors) {
      Contact c{kind, a.point, Eigen::Vector3d::Zero(), a.anchor};
      c.face = a.face;
      const ContactGap g = contact_gap(model, state, c);
      if (g.gap >= 0) continue;
      const double depth = -g.gap;
      const double force =
          contact_stiffness(model, c) * depth + contact_stiffening(model, c) * depth * depth;
      Eigen::Index axis = 0;
      g.box.normal.cwiseAbs().maxCoeff(&axis);
      faces[std::size_t(2 * axis + (g.box.normal(axis) > 0 ? 1 : 0))] += force;
    }
  };
  add(Contact::kNodeCube, state.node_cube);
  add(Contact::kSampleCube, state.sample_cube);
  return faces;
}

}  // namespace handlab::sim
