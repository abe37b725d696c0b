// The contact stage (core/sim/contact.h) on the study hand gripping the fine cube on the floor:
// the candidates it finds, its energies' gradient and Hessian against finite differences, and
// friction's anchors inside Coulomb's cone.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "core/sim/contact.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

using test::GraspScene;

std::vector<Eigen::Vector3d> no_turn(const HandSimModel& model) {
  return std::vector<Eigen::Vector3d>(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
}

// Every surface node within a millimetre of the cube, and every corner on the floor, is a
// candidate; those inside touch; flesh that touched before keeps its anchor or moves it to
// the cone's edge.
TEST(ContactSearch, FindsEveryPointNearASurface) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  std::vector<Contact> contacts;
  find_contacts(model, g.state, contacts);
  int node_cube = 0, touching = 0, corners = 0;
  for (const Contact& c : contacts) {
    const ContactGap gap = contact_gap(model, g.state, c);
    EXPECT_EQ(c.touching, gap.gap < 0);
    node_cube += c.kind == Contact::kNodeCube;
    touching += c.touching && c.kind == Contact::kNodeCube;
    corners += c.kind == Contact::kCornerFloor && c.touching;
    EXPECT_NE(c.kind, Contact::kNodeFloor) << "hand-floor contact is off in the study";
  }
  EXPECT_GE(touching, 4) << "both pads press on the cube";
  EXPECT_GE(corners, 2) << "the cube, tipped a little by the grip, rests on its lower corners";
  for (int node : model.surface_nodes) {
    const Contact probe{Contact::kNodeCube, node, {}, {}};
    if (contact_gap(model, g.state, probe).gap > 0.001) continue;
    EXPECT_TRUE(std::any_of(
        contacts.begin(), contacts.end(),
        [&](const Contact& c) { return c.kind == Contact::kNodeCube && c.point == node; }))
        << "node " << node;
  }
  // An anchor kept from the step before stays, or moves along the surface to the cone's edge.
  for (const Contact& c : contacts) {
    if (c.kind != Contact::kNodeCube || !c.touching) continue;
    const auto old = std::find_if(g.state.node_cube.begin(), g.state.node_cube.end(),
                                  [&](const ContactAnchor& a) { return a.point == c.point; });
    if (old == g.state.node_cube.end()) continue;
    const ContactGap gap = contact_gap(model, g.state, c);
    const double reach = tangent_part(c.normal, gap.x - c.anchor).norm();
    EXPECT_LE(reach, friction_cone(model, c, -gap.gap) * (1 + 1e-9) + 1e-15);
  }
  EXPECT_GT(node_cube, touching);
}

NewtonTerms contact_terms(const HandSimModel& model, const HandSimState& s,
                          const std::vector<Contact>& contacts, bool hessian) {
  NewtonTerms terms = test::empty_terms(model, hessian);
  add_contact_energies(model, s, contacts, terms);
  return terms;
}

HandSimState moved(const HandSimModel& model, const HandSimState& s, const Eigen::VectorXd& d,
                   double t) {
  HandSimState m = s;
  std::vector<Eigen::Vector3d> turned = no_turn(model);
  test::move_by(model, m, turned, d, t);
  return m;
}

// One of the contact energies alone: the normal penalties (the contacts taken as not touching,
// which friction needs), or friction (the springs and kinetic forces: all less the penalties).
struct ContactEnergyPart {
  std::vector<Contact> all, penalties;
  bool friction = false;

  NewtonTerms at(const HandSimModel& model, const HandSimState& s, bool hessian) const {
    NewtonTerms terms = contact_terms(model, s, friction ? all : penalties, hessian);
    if (!friction) return terms;
    const NewtonTerms penalty = contact_terms(model, s, penalties, hessian);
    terms.energy -= penalty.energy;
    terms.gradient -= penalty.gradient;
    return terms;
  }
  Eigen::SparseMatrix<double> hessian(const HandSimModel& model, const HandSimState& s) const {
    const Eigen::SparseMatrix<double> h = test::assembled(model, at(model, s, true), false);
    if (!friction) return h;
    return h - test::assembled(model, contact_terms(model, s, penalties, true), false);
  }
};

class ContactEnergy : public ::testing::TestWithParam<std::string> {};

// The gradient is the energy's slope along the nodes, the cube's translation and its rotation.
// The Hessian is the gradient's derivative along the nodes and the cube's translation (the
// Gauss-Newton Hessian leaves out the surface's curvature under a turn of the cube).
TEST_P(ContactEnergy, GradientAndHessianAreTheEnergysDerivatives) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  ContactEnergyPart part;
  find_contacts(model, g.state, part.all);
  part.penalties = part.all;
  for (Contact& c : part.penalties) c.touching = false;
  part.friction = GetParam() == "friction";
  const NewtonTerms terms = part.at(model, g.state, true);
  ASSERT_GT(terms.gradient.lpNorm<Eigen::Infinity>(), 0.0);
  const Eigen::SparseMatrix<double> hessian = part.hessian(model, g.state);
  ASSERT_GT(hessian.nonZeros(), 0);
  for (double phase : {1.0, 2.0, 3.0}) {
    // 0.1 mm and 0.01 rad at t = 1: steps of 1e-4 of that stay in each contact's face region.
    Eigen::VectorXd along =
        test::only(model, test::direction(model, 1e-4, 1e-2, phase), true, false, false);
    along.tail(6) = test::direction(model, 1e-4, 1e-2, phase + 0.3).tail(6);  // the cube
    const auto [slope, curvature] = test::differences(
        [&](double t) { return part.at(model, moved(model, g.state, along, t), false).energy; },
        1e-4);
    const double slope_scale = terms.gradient.cwiseAbs().dot(along.cwiseAbs());
    EXPECT_NEAR(slope, terms.gradient.dot(along), 1e-6 * slope_scale) << "phase " << phase;
    // Along the nodes and the cube's translation only.
    Eigen::VectorXd straight = along;
    straight.tail(3).setZero();
    const double step = 1e-4;
    const Eigen::VectorXd change =
        (part.at(model, moved(model, g.state, straight, step), true).gradient -
         part.at(model, moved(model, g.state, straight, -step), true).gradient) /
        (2 * step);
    const Eigen::VectorXd expected = hessian * straight;
    const double scale = (Eigen::SparseMatrix<double>(hessian.cwiseAbs()) * straight.cwiseAbs())
                             .lpNorm<Eigen::Infinity>();
    EXPECT_LT((change - expected).lpNorm<Eigen::Infinity>(), 1e-4 * scale) << "phase " << phase;
  }
}

INSTANTIATE_TEST_SUITE_P(Each, ContactEnergy, ::testing::Values("penalty", "friction"),
                         [](const auto& info) { return info.param; });

// After a step, every anchor lies within Coulomb's cone of its point, on the surface's side.
TEST(Friction, AnchorsStayInsideCoulombsCone) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  std::vector<Contact> contacts;
  find_contacts(model, g.state, contacts);
  // The state moved as a step might move it: the anchors must follow.
  HandSimState s = moved(model, g.state, test::direction(model, 2e-4, 0.0, 5.0), 1.0);
  EXPECT_FALSE(friction_changed(model, g.state, contacts))
      << "at the state they were found at, no contact changes";
  const double penetration = update_anchors(model, contacts, s);
  EXPECT_GT(penetration, 0.0);
  EXPECT_LT(penetration, 0.002);
  int anchors = 0;
  for (const auto* list : {&s.node_cube, &s.corner_floor}) {
    for (const ContactAnchor& a : *list) {
      const Contact probe{
          list == &s.node_cube ? Contact::kNodeCube : Contact::kCornerFloor, a.point, {}, a.anchor};
      const ContactGap gap = contact_gap(model, s, probe);
      ASSERT_LT(gap.gap, 0.0);
      const Eigen::Vector3d normal = probe.kind == Contact::kNodeCube
                                         ? gap.box.normal
                                         : model.parameters.floor_normal.normalized();
      EXPECT_LE(tangent_part(normal, gap.x - a.anchor).norm(),
                friction_cone(model, probe, -gap.gap) * (1 + 1e-9) + 1e-15);
      ++anchors;
    }
    EXPECT_TRUE(std::is_sorted(
        list->begin(), list->end(),
        [](const ContactAnchor& x, const ContactAnchor& y) { return x.point < y.point; }))
        << "find_contacts looks anchors up by point";
  }
  EXPECT_GE(anchors, 2) << "the pads' anchors at least";
}

}  // namespace
}  // namespace handlab::sim
