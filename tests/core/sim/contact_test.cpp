// The contact stage (core/sim/contact.h) on the study hand gripping the fine cube on the floor:
// the candidates it finds, its energies' gradient and Hessian against finite differences, and
// friction's anchors inside Coulomb's cone.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "core/mesh/tet_mesh.h"
#include "core/sim/contact.h"
#include "core/sim/contact_damping.h"
#include "core/sim/sim_parameter_names.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

using test::GraspScene;

std::vector<Eigen::Vector3d> no_turn(const HandSimModel& model) {
  return std::vector<Eigen::Vector3d>(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
}

// Every surface node and skin sample within a millimetre of the cube is a candidate; those
// inside touch; flesh that touched before keeps its anchor or moves it to the cone's edge.
TEST(ContactSearch, FindsEveryPointNearASurface) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  std::vector<Contact> contacts;
  find_contacts(model, g.state, contacts);
  int on_the_cube = 0, nodes_touching = 0, samples_touching = 0;
  std::vector<Eigen::Vector3d> pressed;  // the cube's faces flesh presses on (cube frame)
  for (const Contact& c : contacts) {
    const ContactGap gap = contact_gap(model, g.state, c);
    EXPECT_EQ(c.touching, gap.gap < 0);
    on_the_cube += on_cube(c);
    if (c.touching && on_cube(c)) pressed.push_back(c.normal);
    nodes_touching += c.touching && c.kind == Contact::kNodeCube;
    samples_touching += c.touching && c.kind == Contact::kSampleCube;
    EXPECT_NE(c.kind, Contact::kNodeFloor) << "hand-floor contact is off in the study";
  }
  EXPECT_TRUE(std::any_of(pressed.begin(), pressed.end(), [&](const Eigen::Vector3d& n) {
    return std::any_of(pressed.begin(), pressed.end(),
                       [&](const Eigen::Vector3d& m) { return n.dot(m) < -0.9; });
  })) << "both pads press on the cube, on opposite faces";
  EXPECT_GT(nodes_touching, 0) << "the pads' nodes press";
  EXPECT_GT(samples_touching, 0) << "the skin between the pads' nodes presses too";
  auto found = [&](Contact::Kind kind, int point) {
    return std::any_of(contacts.begin(), contacts.end(),
                       [&](const Contact& c) { return c.kind == kind && c.point == point; });
  };
  for (int node : model.surface_nodes) {
    const Contact probe{Contact::kNodeCube, node, {}, {}};
    if (contact_gap(model, g.state, probe).gap > 0.001) continue;
    EXPECT_TRUE(found(Contact::kNodeCube, node)) << "node " << node;
  }
  for (int i = 0; i < int(model.skin_samples.size()); ++i) {
    const Contact probe{Contact::kSampleCube, i, {}, {}};
    if (contact_gap(model, g.state, probe).gap > 0.001) continue;
    EXPECT_TRUE(found(Contact::kSampleCube, i)) << "skin sample " << i;
  }
  // An anchor kept from the step before stays, or moves along the surface to the cone's edge.
  for (const Contact& c : contacts) {
    if (!on_cube(c) || !c.touching) continue;
    const auto& list = c.kind == Contact::kNodeCube ? g.state.node_cube : g.state.sample_cube;
    const auto old = std::find_if(list.begin(), list.end(),
                                  [&](const ContactAnchor& a) { return a.point == c.point; });
    if (old == list.end()) continue;
    const ContactGap gap = contact_gap(model, g.state, c);
    const double reach = tangent_part(c.normal, gap.x - c.anchor).norm();
    EXPECT_LE(reach, friction_cone(model, c, -gap.gap) * (1 + 1e-9) + 1e-15);
  }
  EXPECT_GT(on_the_cube, int(pressed.size()));
}

// A cube on the floor: its corners below it touch. As the fingers close on the cube's top, it
// lies tipped a little on its lower corners.
TEST(ContactSearch, FindsTheCubesCornersOnTheFloor) {
  const GraspScene& g = test::pinch_stage(1.25);
  const HandSimModel& model = g.scene.model;
  std::vector<Contact> contacts;
  find_contacts(model, g.state, contacts);
  int corners = 0;
  for (const Contact& c : contacts) {
    if (c.kind != Contact::kCornerFloor) continue;
    EXPECT_EQ(c.touching, contact_gap(model, g.state, c).gap < 0) << "corner " << c.point;
    corners += c.touching;
  }
  EXPECT_GE(corners, 2) << "the cube rests on its lower corners";
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
// The Hessian is the gradient's derivative along the nodes and the cube's translation, but for
// the cube's torque: the Gauss-Newton Hessian leaves out how the torque's arm moves with the
// point (f x dx, as large as the depth is against the arm) and the surface's curvature under a
// turn of the cube.
TEST_P(ContactEnergy, GradientAndHessianAreTheEnergysDerivatives) {
  // The grip, and the cube on its corners on the floor (their penalty and friction).
  for (double time : {test::gripping_fine_cube().time, 1.25}) {
    SCOPED_TRACE(time);
    const GraspScene& g = test::pinch_stage(time);
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
      Eigen::VectorXd change =
          (part.at(model, moved(model, g.state, straight, step), true).gradient -
           part.at(model, moved(model, g.state, straight, -step), true).gradient) /
          (2 * step);
      Eigen::VectorXd expected = hessian * straight;
      change.tail(3).setZero();  // the cube's torque
      expected.tail(3).setZero();
      const double scale = (Eigen::SparseMatrix<double>(hessian.cwiseAbs()) * straight.cwiseAbs())
                               .lpNorm<Eigen::Infinity>();
      EXPECT_LT((change - expected).lpNorm<Eigen::Infinity>(), 1e-4 * scale) << "phase " << phase;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Each, ContactEnergy, ::testing::Values("penalty", "friction"),
                         [](const auto& info) { return info.param; });

// After a step, every anchor lies within Coulomb's cone of its point, on the surface's side.
TEST(Friction, AnchorsStayInsideCoulombsCone) {
  // The grip, and the cube on its corners on the floor (their penalty and friction).
  for (double time : {test::gripping_fine_cube().time, 1.25}) {
    SCOPED_TRACE(time);
    const GraspScene& g = test::pinch_stage(time);
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
    const std::pair<const std::vector<ContactAnchor>*, Contact::Kind> lists[] = {
        {&s.node_cube, Contact::kNodeCube},
        {&s.sample_cube, Contact::kSampleCube},
        {&s.corner_floor, Contact::kCornerFloor}};
    for (const auto& [list, kind] : lists) {
      for (const ContactAnchor& a : *list) {
        const Contact probe{kind, a.point, {}, a.anchor, a.face};  // the face it pushes out through
        const ContactGap gap = contact_gap(model, s, probe);
        ASSERT_LT(gap.gap, 0.0);
        const Eigen::Vector3d normal =
            on_cube(probe) ? gap.box.normal : model.parameters.floor_normal.normalized();
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
    EXPECT_FALSE(s.sample_cube.empty()) << "the skin between the pads' nodes holds too";
  }
}

// Two pairs of materials: the skin's coefficient sets the cone of flesh on the cube, the
// floor's that of a cube corner on the floor, each in proportion.
TEST(Friction, TheSkinsCoefficientIsTheFleshsOnTheCubeTheFloorsTheCubesOnTheFloor) {
  HandSimModel model = test::gripping_fine_cube().scene.model;
  const double depth = 2e-4;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const std::vector<Contact> skin = {{Contact::kNodeCube, 0, zero, zero},
                                     {Contact::kSampleCube, 0, zero, zero}},
                             floor = {{Contact::kCornerFloor, 0, zero, zero},
                                      {Contact::kNodeFloor, 0, zero, zero}};
  auto cones = [&](const std::vector<Contact>& contacts) {
    std::vector<double> out;
    for (const Contact& c : contacts) out.push_back(friction_cone(model, c, depth));
    return out;
  };
  const std::vector<double> skin_before = cones(skin), floor_before = cones(floor);
  set_sim_parameter(model.parameters, "skin_friction", 1.5 * model.parameters.skin_friction);
  set_sim_parameter(model.parameters, "friction", 0.5 * model.parameters.friction);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_DOUBLE_EQ(cones(skin)[k], 1.5 * skin_before[k]) << "flesh on the cube, kind " << k;
    EXPECT_DOUBLE_EQ(cones(floor)[k], 0.5 * floor_before[k]) << "on the floor, kind " << k;
  }
}

// A corner of the cube pressed into the middle of a skin face, between its nodes: the face's
// skin sample finds it and pushes the face's nodes and the cube apart, a third of the force on
// each node. With the nodes alone nothing touches, and the corner goes on into the flesh.
TEST(ContactSearch, ASkinSampleMeetsACornerBetweenNodes) {
  const mesh::TetMesh tet{{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.03, 0, 0.02),
                           Eigen::Vector3d(0, 0.03, 0.02), Eigen::Vector3d(0, 0, 0.05)},
                          {{0, 1, 2, 3}}};
  // The face (0, 1, 2) has its centroid at (0.01, 0.01, 0.0133); the corner (+, +, +) of the
  // cube, turned to point along the face's inward normal, 0.5 mm past it.
  auto pressed = [&](int samples, std::vector<Contact>& contacts) {
    SimParameters parameters;
    parameters.skin_samples = samples;
    parameters.floor_height = -1.0;  // out of the way
    HandSimModel model = make_soft_body_sim_model(tet, parameters);
    const Eigen::Vector3d a = model.rest[0], b = model.rest[1], c = model.rest[2];
    const Eigen::Vector3d inward = (b - a).cross(c - a).normalized();  // towards node 3
    EXPECT_GT(inward.dot(model.rest[3] - a), 0.0);
    HandSimState s;
    s.node_position = model.rest;
    s.node_velocity.assign(model.rest.size(), Eigen::Vector3d::Zero());
    s.tet_rotation.assign(1, Eigen::Quaterniond::Identity());
    s.cube_pose.rotation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::Ones(), inward);
    const Eigen::Vector3d corner = s.cube_pose.rotation * corner_offset(model, 7);
    s.cube_pose.position = (a + b + c) / 3 + 0.0005 * inward - corner;
    find_contacts(model, s, contacts);
    return std::tuple{model, s, inward};
  };
  std::vector<Contact> contacts;
  const auto [model, s, inward] = pressed(1, contacts);
  ASSERT_EQ(model.skin_samples.size(), 4u);
  int touching = 0;
  for (const Contact& c : contacts) {
    EXPECT_FALSE(c.kind == Contact::kNodeCube && c.touching) << "node " << c.point;
    touching += c.kind == Contact::kSampleCube && c.touching;
  }
  EXPECT_EQ(touching, 1);
  NewtonTerms terms = test::empty_terms(model, true);
  add_contact_energies(model, s, contacts, terms);
  EXPECT_GT(terms.energy, 0.0);
  // Forces (minus the gradient): each of the face's nodes pushed into the flesh, equally.
  const Eigen::Vector3d f0 = -terms.gradient.segment<3>(0);
  EXPECT_GT(f0.dot(inward), 0.0);
  for (int n : {1, 2})
    EXPECT_LT((-terms.gradient.segment<3>(3 * n) - f0).norm(), 1e-12 * f0.norm());
  EXPECT_EQ(terms.gradient.segment<3>(9).norm(), 0.0) << "node 3 is not on the face";
  const Eigen::Vector3d on_cube = -terms.gradient.segment<3>(3 * cube_block(model));
  EXPECT_LT((on_cube + 3 * f0).norm(), 1e-9 * f0.norm()) << "and the cube back, as hard";
  HandSimState after = s;
  update_anchors(model, contacts, after);
  EXPECT_EQ(after.sample_cube.size(), 1u);

  std::vector<Contact> nodes_only;
  pressed(0, nodes_only);
  EXPECT_TRUE(std::none_of(nodes_only.begin(), nodes_only.end(),
                           [](const Contact& c) { return c.touching; }));
}

// A flesh point pressed into a side face of the cube near its bottom edge, then deeper than
// its height above the bottom: by the nearest face it pushes the cube up through the bottom;
// with contact_keeps_face it pushes it on through the side face it came through.
TEST(ContactSearch, AFleshPointKeepsTheFaceItCameThrough) {
  const mesh::TetMesh tet{{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.03, 0, 0),
                           Eigen::Vector3d(0.03, 0.03, 0), Eigen::Vector3d(0.03, 0, 0.03)},
                          {{0, 1, 2, 3}}};
  auto force_on_cube = [&](bool keep_face) {
    SimParameters parameters;
    parameters.floor_height = -1.0;  // out of the way
    set_sim_parameter(parameters, "contact_keeps_face", keep_face ? 1 : 0);
    const HandSimModel model = make_soft_body_sim_model(tet, parameters);
    HandSimState s;
    s.node_velocity.assign(model.rest.size(), Eigen::Vector3d::Zero());
    s.tet_rotation.assign(1, Eigen::Quaterniond::Identity());
    s.node_position = model.rest;
    // Node 0 0.2 mm outside the +x face, 0.3 mm above the bottom (the cube at the origin).
    const double half = model.cube_half.x();
    s.node_position[0] = Eigen::Vector3d(half + 0.0002, -half + 0.0003, 0.0);
    std::vector<Contact> contacts;
    find_contacts(model, s, contacts);
    EXPECT_EQ(contacts.size(), 1u);
    if (contacts.size() != 1) return Eigen::Vector3d(Eigen::Vector3d::Constant(NAN));
    EXPECT_EQ(contacts.front().face, keep_face ? 1 : -1);
    // Then 0.6 mm inside it: deeper than its height above the bottom.
    s.node_position[0].x() = half - 0.0006;
    update_anchors(model, contacts, s);
    find_contacts(model, s, contacts);
    if (contacts.size() != 1) return Eigen::Vector3d(Eigen::Vector3d::Constant(NAN));
    EXPECT_TRUE(contacts.front().touching);
    NewtonTerms terms = test::empty_terms(model, true);
    add_contact_energies(model, s, contacts, terms);
    return Eigen::Vector3d(-terms.gradient.segment<3>(3 * cube_block(model)));
  };
  const Eigen::Vector3d nearest = force_on_cube(false), kept = force_on_cube(true);
  EXPECT_GT(nearest.y(), 0.0) << "pushed up through the bottom";
  EXPECT_NEAR(nearest.x(), 0.0, 1e-12);
  EXPECT_LT(kept.x(), 0.0) << "pushed on through the +x face";
  EXPECT_NEAR(kept.y(), 0.0, 1e-12);
  EXPECT_GT(-kept.x(), 1.5 * nearest.y()) << "0.6 mm deep, not 0.3 mm";
}

// The contact damper (contact_damping.h) on the hand gripping the light cube: nothing where the
// state is the step's start; the cube moved by 10 um, each touching point's spring of
// contact_damping times its force at the start over h, along its normal, from where it lay; its
// gradient the energy's slope.
TEST(ContactDamping, ResistsTheDepthsRateInProportionToThePenaltysForce) {
  const GraspScene& g = test::gripping_fine_cube();
  HandSimModel model = g.scene.model;
  model.parameters.contact_damping = 2.0;  // s/m
  std::vector<Contact> contacts;
  find_contacts(model, g.state, contacts);
  std::vector<ContactDamper> dampers;
  set_contact_dampers(model, g.state, contacts, dampers);
  ASSERT_EQ(dampers.size(), contacts.size());
  auto damping = [&](const HandSimState& s, bool hessian) {
    NewtonTerms terms = test::empty_terms(model, hessian);
    add_contact_damping(model, s, contacts, dampers, terms);
    return terms;
  };

  const Eigen::Vector3d shift(1e-5, -0.4e-5, 0.2e-5);
  HandSimState moved_cube = g.state;
  moved_cube.cube_pose.position += shift;
  double expected = 0.0;
  int damped = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (!on_cube(c) || !c.touching || dampers[i].force <= 0) continue;
    const Eigen::Vector3d q = moved_cube.cube_pose.rotation.conjugate() *
                              (flesh_point(model, moved_cube, c) - moved_cube.cube_pose.position);
    if (flesh_on_cube(model, q, c.face).distance >= 0) continue;
    ++damped;
    const double rate = c.across.dot(-shift);  // the point's move against the cube's
    expected += 0.5 * model.parameters.contact_damping * dampers[i].force /
                model.parameters.time_step * rate * rate;
  }
  ASSERT_GE(damped, 2) << "both pads";
  const double h = model.parameters.time_step;
  EXPECT_NEAR(damping(moved_cube, false).energy, h * h * expected, 1e-9 * h * h * expected);

  const NewtonTerms terms = damping(moved_cube, true);
  const NewtonTerms at_start = damping(g.state, false);  // zero but for the frames' rounding
  EXPECT_LT(at_start.energy, 1e-12 * terms.energy);
  EXPECT_LT(at_start.gradient.lpNorm<Eigen::Infinity>(),
            1e-9 * terms.gradient.lpNorm<Eigen::Infinity>());
  for (double phase : {1.0, 2.0}) {
    Eigen::VectorXd along =
        test::only(model, test::direction(model, 1e-6, 1e-4, phase), true, false, false);
    along.tail(6) = test::direction(model, 1e-6, 1e-4, phase + 0.3).tail(6);
    const auto [slope, curvature] = test::differences(
        [&](double t) { return damping(moved(model, moved_cube, along, t), false).energy; }, 1e-3);
    const double scale = terms.gradient.cwiseAbs().dot(along.cwiseAbs());
    EXPECT_NEAR(slope, terms.gradient.dot(along), 1e-6 * scale) << "phase " << phase;
  }
}

}  // namespace
}  // namespace handlab::sim
