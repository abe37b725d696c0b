// The bodies' stage (core/sim/body_energies.h), each energy alone: coupling, joints, tracking,
// its damping, gravity and the kinetic terms. Gradients against central differences of the energy
// along directions through every unknown (node positions, the bodies' translations and rotation
// vectors) on the hand gripping the fine cube, where every spring is stretched; Hessians against
// central differences of the gradient where the springs are at rest length (the hand at rest,
// its targets where its bones are), where the Gauss-Newton Hessian J'KJ is the Hessian, and the
// kinetic terms' everywhere (they are quadratic), and the tracking's damping's where the bones have
// moved since the step's start but not turned (its turn's Hessian, like the tracking's, is the
// rotation vector's at rest).
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/sim/body_energies.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

using test::GraspScene;

// One energy: adds itself to the terms at a state.
using Energy =
    std::function<void(const HandSimState&, const std::vector<Eigen::Vector3d>&, NewtonTerms&)>;

// The model with the tracking's damping on, saturating (a bone moved 1 mm in a step is past v0).
const HandSimModel& damped(const HandSimModel& model) {
  static const HandSimModel copy = [&] {
    HandSimModel m = model;
    m.parameters.tracking_damping = 0.025;
    m.parameters.tracking_damping_speed = 0.07;
    return m;
  }();
  return copy;
}

// The energy named `name`, with the targets and the step's start it reads.
Energy energy_named(const std::string& name, const HandSimModel& model,
                    const std::vector<RigidPose>& targets, const HandSimState& start) {
  if (name == "coupling")
    return [&](const HandSimState& s, const auto&, NewtonTerms& t) { add_coupling(model, s, t); };
  if (name == "joints")
    return [&](const HandSimState& s, const auto&, NewtonTerms& t) { add_joints(model, s, t); };
  if (name == "tracking")
    return [&](const HandSimState& s, const auto&, NewtonTerms& t) {
      add_tracking(model, s, targets, t);
    };
  if (name == "tracking_damping")
    return [&](const HandSimState& s, const auto&, NewtonTerms& t) {
      add_tracking_damping(damped(model), s, start, t);
    };
  if (name == "gravity")
    return [&](const HandSimState& s, const auto&, NewtonTerms& t) { add_gravity(model, s, t); };
  return [&](const HandSimState& s, const std::vector<Eigen::Vector3d>& turned, NewtonTerms& t) {
    add_kinetic(model, s, turned, start, t);
  };
}

struct At {
  HandSimState state;
  std::vector<Eigen::Vector3d> turned;
};

// Terms of one energy at the state moved by t d.
NewtonTerms terms_at(const HandSimModel& model, const At& at, const Energy& energy,
                     const Eigen::VectorXd& d, double t, bool hessian) {
  HandSimState s = at.state;
  std::vector<Eigen::Vector3d> turned = at.turned;
  test::move_by(model, s, turned, d, t);
  NewtonTerms terms = test::empty_terms(model, hessian);
  energy(s, turned, terms);
  return terms;
}

// The kinetic terms' start: the state a step before, moving towards it.
HandSimState step_before(const HandSimModel& model, const HandSimState& s) {
  HandSimState start = s;
  std::vector<Eigen::Vector3d> turned(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
  test::move_by(model, start, turned, test::direction(model, 1e-3, 0.02, 4.0), -1.0);
  return start;
}

// The tracking's damping's start: every bone 1.1 mm back along a line (a step at 0.14 m/s, past
// its saturating speed), none turned.
HandSimState moved_not_turned(const HandSimState& s) {
  HandSimState start = s;
  for (RigidPose& pose : start.bone_pose) pose.position -= Eigen::Vector3d(1e-3, -4e-4, 2e-4);
  return start;
}

class BodyEnergy : public ::testing::TestWithParam<std::string> {};

TEST_P(BodyEnergy, GradientIsTheEnergysSlope) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  const HandSimState start = step_before(model, g.state);
  At at{g.state, std::vector<Eigen::Vector3d>(std::size_t(model.bone_count() + 1),
                                              Eigen::Vector3d::Constant(0.01))};
  const Energy energy = energy_named(GetParam(), model, g.targets, start);
  const NewtonTerms terms =
      terms_at(model, at, energy, Eigen::VectorXd::Zero(model.dof_count()), 0.0, true);
  EXPECT_GT(terms.gradient.lpNorm<Eigen::Infinity>(), 0.0);
  for (double phase : {1.0, 2.0}) {
    const Eigen::VectorXd d = test::direction(model, 1.0, 1.0, phase);
    const auto [slope, curvature] = test::differences(
        [&](double t) { return terms_at(model, at, energy, d, t, false).energy; }, 1e-6);
    const double scale = terms.gradient.cwiseAbs().dot(d.cwiseAbs());
    EXPECT_NEAR(slope, terms.gradient.dot(d), 1e-6 * scale) << "phase " << phase;
  }
}

TEST_P(BodyEnergy, HessianIsTheGradientsDerivativeAtRestLength) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  // The hand at rest where the pinch starts, its targets its bones' poses: coupling springs,
  // joints and tracking at rest length.
  At at{initial_state(model, g.scene.skeleton, g.scene.script.start_root(), g.state.cube_pose),
        std::vector<Eigen::Vector3d>(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero())};
  const std::vector<RigidPose> targets = at.state.bone_pose;
  const HandSimState start =
      GetParam() == "tracking_damping" ? moved_not_turned(at.state) : step_before(model, at.state);
  const Energy energy = energy_named(GetParam(), model, targets, start);
  const NewtonTerms terms =
      terms_at(model, at, energy, Eigen::VectorXd::Zero(model.dof_count()), 0.0, true);
  const bool kinetic = GetParam() == "kinetic";
  const Eigen::SparseMatrix<double> hessian = test::assembled(model, terms, kinetic);
  for (double phase : {1.0, 2.0}) {
    const Eigen::VectorXd d = test::direction(model, 1.0, 1.0, phase);
    const double step = 1e-6;
    const Eigen::VectorXd change = (terms_at(model, at, energy, d, step, true).gradient -
                                    terms_at(model, at, energy, d, -step, true).gradient) /
                                   (2 * step);
    if (GetParam() == "gravity") {  // a linear potential
      EXPECT_EQ(hessian.nonZeros(), 0);
      EXPECT_LT(change.lpNorm<Eigen::Infinity>(), 1e-9 * terms.gradient.norm());
      continue;
    }
    const Eigen::VectorXd expected = hessian * d;
    const double scale =
        (Eigen::SparseMatrix<double>(hessian.cwiseAbs()) * d.cwiseAbs()).lpNorm<Eigen::Infinity>();
    ASSERT_GT(scale, 0.0);
    EXPECT_LT((change - expected).lpNorm<Eigen::Infinity>(), 1e-5 * scale) << "phase " << phase;
  }
}

INSTANTIATE_TEST_SUITE_P(Each, BodyEnergy,
                         ::testing::Values("coupling", "joints", "tracking", "tracking_damping",
                                           "gravity", "kinetic"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace handlab::sim
