#include "core/sim/contact.h"

namespace handlab::sim {
namespace {

// The normal penalty of a point at a signed distance < 0 from a surface of outward normal n:
// the energy k d^2/2 + k3 d^3/3 of the depth d, its force (k d + k3 d^2) n, its curvature
// (k + 2 k3 d) n n'.
void add_penalty(NewtonTerms& terms, const PointJacobian& p, const Eigen::Vector3d& n,
                 double distance, double k, double k3) {
  const double scale = terms.scale;
  const double d = -distance;
  terms.energy += scale * d * d * (0.5 * k + k3 * d / 3.0);
  const Eigen::Vector3d f = (scale * (k + k3 * d) * distance) * n;
  for (int a = 0; a < p.count; ++a)
    terms.gradient.segment<3>(3 * p.block[std::size_t(a)]) += p.j[std::size_t(a)].transpose() * f;
  terms.add_curvature(p, (k + 2.0 * k3 * d) * n * n.transpose());
}

}  // namespace

void add_contact_energies(const HandSimModel& model, const HandSimState& s,
                          const std::vector<Contact>& contacts, NewtonTerms& terms) {
  const SimParameters& par = model.parameters;
  const Eigen::Vector3d nf = par.floor_normal.normalized();
  const Eigen::Matrix3d cube_r = s.cube_pose.rotation.toRotationMatrix();
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const int cube = cube_block(model);
  for (const Contact& c : contacts) {
    const double k = contact_stiffness(model, c);
    const bool corner = c.kind == Contact::kCornerFloor;
    PointJacobian p = corner ? PointJacobian() : flesh_point_jacobian(model, c);
    Eigen::Vector3d x;
    if (corner) {
      const Eigen::Vector3d arm = cube_r * corner_offset(model, c.point);
      x = s.cube_pose.position + arm;
      p.add_body_point(cube, arm, 1.0);
    } else {
      x = flesh_point(model, s, c);
    }
    if (!on_cube(c)) {
      const double height = nf.dot(x) - par.floor_height;
      if (height < 0)
        add_penalty(terms, p, nf, height, k, contact_stiffening(model, c));
      else if (c.curved)
        terms.add_curvature(p, k * nf * nf.transpose());
      if (!c.touching || height >= 0) continue;  // no friction from a point that left
      if (c.sliding)
        terms.add_force(p, c.friction_force * c.slip, x);
      else
        terms.add_spring(p, k * (identity - c.normal * c.normal.transpose()), x - c.anchor);
      continue;
    }
    // Against the cube: the surface point and the anchor move with it.
    const BoxProximity b =
        flesh_on_cube(model, s.cube_pose.rotation.conjugate() * (x - s.cube_pose.position), c.face);
    if (b.distance < 0 || c.curved) {
      const Eigen::Vector3d n = cube_r * b.normal, surface = s.cube_pose.point(b.closest);
      PointJacobian normal_part = p;
      normal_part.add_body_point(cube, surface - s.cube_pose.position, -1.0);
      if (b.distance < 0)
        add_penalty(terms, normal_part, n, b.distance, k, contact_stiffening(model, c));
      else
        terms.add_curvature(normal_part, k * n * n.transpose());
    }
    if (!c.touching || b.distance >= 0) continue;  // no pull from a point that left
    const Eigen::Vector3d anchor = s.cube_pose.point(c.anchor), &n = c.across;
    PointJacobian friction_part = p;
    friction_part.add_body_point(cube, anchor - s.cube_pose.position, -1.0);
    if (c.sliding)
      terms.add_force(friction_part, c.friction_force * (cube_r * c.slip), x - anchor);
    else
      terms.add_spring(friction_part, k * (identity - n * n.transpose()), x - anchor);
  }
}

}  // namespace handlab::sim
