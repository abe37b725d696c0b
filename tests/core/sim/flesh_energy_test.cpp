// The flesh stage (core/sim/flesh_energy.h) on the study hand gripping the fine cube: its
// gradient and Hessian against finite differences of its energy, with the tets' rotations held
// as Newton holds them; below the stiffening threshold, the textbook element's energy and
// forces; the same on one worker as on two.
#include <algorithm>

#include <gtest/gtest.h>

#include "core/sim/flesh_energy.h"
#include "tests/core/sim/reference/corotated_element.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

using test::GraspScene;

// The flesh's terms at the state (its rotations extracted there, into `state`).
NewtonTerms flesh_terms(const HandSimModel& model, HandSimState& state, int workers = 2) {
  NewtonTerms terms = test::empty_terms(model, true);
  ThreadPool pool(workers);
  FleshBuffers buffers;
  add_flesh(model, state, terms, pool, buffers);
  return terms;
}

int stiffened_tets(const NewtonTerms& terms) {
  int count = 0;
  for (const TetTerms4& t : terms.tets)
    for (int l = 0; l < kTetBatch; ++l) count += t.q[0][l] != 0 || t.q[1][l] != 0;
  return count;
}

TEST(FleshEnergy, GradientAndHessianAreTheEnergysDerivatives) {
  const GraspScene& g = test::gripping_fine_cube();
  // The energy's own Hessian: no blend below the threshold.
  HandSimModel model = g.scene.model;
  model.parameters.stiffening_blend = 0.0;
  HandSimState state = g.state;
  const NewtonTerms terms = flesh_terms(model, state);
  ASSERT_GT(stiffened_tets(terms), 10) << "the grip stiffens some tets";
  const Eigen::SparseMatrix<double> hessian = test::assembled(model, terms, false);
  const double tets = double(model.tets.size());
  // The energy along d, the rotations held where the terms found them.
  auto energy_along = [&](const Eigen::VectorXd& d) {
    return [&, d](double t) {
      HandSimState moved = state;
      std::vector<Eigen::Vector3d> turned(std::size_t(model.bone_count() + 1),
                                          Eigen::Vector3d::Zero());
      test::move_by(model, moved, turned, d, t);
      return flesh_energy(model, moved, 0, model.tets.size(), terms.scale);
    };
  };
  for (double phase : {1.0, 2.0, 3.0}) {
    const Eigen::VectorXd d =
        test::only(model, test::direction(model, 1.0, 0.0, phase), true, false, false);
    // Steps of 1e-8 m move a tet's strain by about 1e-5: a tet that crosses the stiffening
    // threshold within them (where the energy's curvature jumps) is rare, and its share small.
    const double step = 1e-8;
    const auto [slope, curvature] = test::differences(energy_along(d), step);
    const double expected_slope = terms.gradient.dot(d);
    const double slope_scale = terms.gradient.cwiseAbs().dot(d.cwiseAbs());
    EXPECT_NEAR(slope, expected_slope, 1e-7 * slope_scale) << "phase " << phase;
    const double expected_curvature = d.dot(hessian * d);
    EXPECT_NEAR(curvature, expected_curvature, 1e-4 * expected_curvature) << "phase " << phase;
    // The mixed second derivative of two directions (polarisation): the Hessian's off-diagonal
    // blocks, not only its quadratic form.
    const Eigen::VectorXd e =
        test::only(model, test::direction(model, 1.0, 0.0, phase + 0.5), true, false, false);
    const double mixed = (energy_along(d + e)(step) - energy_along(d - e)(step) -
                          energy_along(e - d)(step) + energy_along(-d - e)(step)) /
                         (4 * step * step);
    const double expected_mixed = d.dot(hessian * e);
    EXPECT_NEAR(mixed, expected_mixed, 1e-4 * std::sqrt(expected_curvature * e.dot(hessian * e)))
        << "phase " << phase;
  }
  EXPECT_GT(tets, 2000);
}

// The blend below the stiffening threshold changes Newton's matrix only: the same energy and
// forces, the same terms beyond the threshold and below the band; in the band the stiffening's
// curvature added, which makes the matrix larger (a step from below shorter), never smaller.
TEST(FleshEnergy, TheBlendAddsCurvatureBelowTheThresholdOnly) {
  const GraspScene& g = test::gripping_fine_cube();
  HandSimModel sharp = g.scene.model;
  sharp.parameters.stiffening_blend = 0.0;
  const HandSimModel& blended = g.scene.model;
  ASSERT_GT(blended.parameters.stiffening_blend, 0.0) << "the default blends";
  HandSimState sharp_state = g.state, blended_state = g.state;
  const NewtonTerms a = flesh_terms(sharp, sharp_state), b = flesh_terms(blended, blended_state);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_EQ(a.gradient, b.gradient);
  int in_band = 0;
  for (std::size_t k = 0; k < a.tets.size(); ++k)
    for (int l = 0; l < kTetBatch; ++l) {
      for (int i = 0; i < 12; ++i) ASSERT_EQ(a.tets[k].rotated[i][l], b.tets[k].rotated[i][l]);
      ASSERT_EQ(a.tets[k].vmu[l], b.tets[k].vmu[l]);
      ASSERT_EQ(a.tets[k].vlambda[l], b.tets[k].vlambda[l]);
      bool same_q = true, sharp_q = false;
      for (int i = 0; i < 12; ++i) {
        same_q = same_q && a.tets[k].q[i][l] == b.tets[k].q[i][l];
        sharp_q = sharp_q || a.tets[k].q[i][l] != 0;
      }
      if (!same_q) {
        EXPECT_FALSE(sharp_q) << "a tet beyond the threshold has the same terms";
        ++in_band;
      }
    }
  EXPECT_GT(in_band, 0) << "the grip has tets in the band";
  const Eigen::SparseMatrix<double> difference =
      test::assembled(blended, b, false) - test::assembled(sharp, a, false);
  for (double phase : {1.0, 2.0, 3.0}) {
    const Eigen::VectorXd d =
        test::only(blended, test::direction(blended, 1.0, 0.0, phase), true, false, false);
    EXPECT_GE(d.dot(difference * d), 0.0) << "phase " << phase;
  }
}

// Newton's matrix is continuous where a tet's strain crosses the threshold: with the blend, a
// stretch just below and just above it give nearly the same matrix; without, they differ by
// the stiffening's curvature (20 times the flesh's).
TEST(FleshEnergy, TheMatrixIsContinuousAcrossTheThreshold) {
  const mesh::TetMesh tet{{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0, 0),
                           Eigen::Vector3d(0, 0.01, 0), Eigen::Vector3d(0, 0, 0.01)},
                          {{0, 1, 2, 3}}};
  auto jump = [&](double blend) {
    SimParameters parameters;
    parameters.stiffening_blend = blend;
    const HandSimModel model = make_soft_body_sim_model(tet, parameters);
    auto matrix = [&](double stretch) {  // along x: a strain norm of `stretch`
      HandSimState s;
      s.node_position = model.rest;
      for (Eigen::Vector3d& x : s.node_position) x.x() *= 1.0 + stretch;
      s.tet_rotation.assign(1, Eigen::Quaterniond::Identity());
      NewtonTerms terms = test::empty_terms(model, true);
      ThreadPool pool(1);
      FleshBuffers buffers;
      add_flesh(model, s, terms, pool, buffers);
      return Eigen::MatrixXd(test::assembled(model, terms, false));
    };
    const double threshold = parameters.stiffening_strain;
    const Eigen::MatrixXd below = matrix(threshold - 1e-7), above = matrix(threshold + 1e-7);
    return (above - below).norm() / below.norm();
  };
  EXPECT_LT(jump(0.2), 1e-5);
  EXPECT_GT(jump(0.0), 1.0);
}

// Below the stiffening threshold the flesh is the textbook co-rotational element: the same
// energy and forces as 1/2 u'Ku with K the 12x12 stiffness, tet by tet.
TEST(FleshEnergy, BelowTheThresholdIsTheTextbookElement) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  HandSimState state =
      initial_state(model, g.scene.skeleton, g.scene.script.start_root(), g.state.cube_pose);
  std::vector<Eigen::Vector3d> turned(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
  test::move_by(model, state, turned, test::direction(model, 1e-5, 0.0), 1.0);
  const NewtonTerms terms = flesh_terms(model, state);
  ASSERT_EQ(stiffened_tets(terms), 0);
  double energy = 0.0;
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * model.node_count());
  for (std::size_t e = 0; e < model.tets.size(); ++e) {
    const TetElement& t = model.tets[e];
    std::array<Eigen::Vector3d, 4> x, rest;
    for (int a = 0; a < 4; ++a) {
      x[std::size_t(a)] = state.node_position[std::size_t(t.nodes[std::size_t(a)])];
      rest[std::size_t(a)] = model.rest[std::size_t(t.nodes[std::size_t(a)])];
    }
    // The element's rotation as the flesh found it (the hand's root turns the rest shape).
    const Eigen::Matrix3d rotation = state.tet_rotation[e].toRotationMatrix();
    ElementEvaluation out;
    evaluate_corotated(corotated_stiffness(t, model.parameters.flesh), rest, x, rotation, out,
                       false);
    energy += out.energy;
    for (int a = 0; a < 4; ++a)
      gradient.segment<3>(3 * t.nodes[std::size_t(a)]) += out.gradient.segment<3>(3 * a);
  }
  EXPECT_NEAR(terms.energy, terms.scale * energy, 1e-9 * terms.scale * energy);
  const Eigen::VectorXd ours = terms.gradient.head(3 * model.node_count());
  EXPECT_LT((ours - terms.scale * gradient).lpNorm<Eigen::Infinity>(),
            1e-9 * terms.scale * gradient.lpNorm<Eigen::Infinity>());
}

// One worker or two: the same energy and forces to rounding (the order they are summed in
// differs), the same terms bit for bit.
TEST(FleshEnergy, OneWorkerAsTwo) {
  const GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  HandSimState one_state = g.state, two_state = g.state;
  const NewtonTerms one = flesh_terms(model, one_state, 1), two = flesh_terms(model, two_state, 2);
  EXPECT_NEAR(one.energy, two.energy, 1e-12 * std::abs(one.energy));
  EXPECT_LT((one.gradient - two.gradient).lpNorm<Eigen::Infinity>(),
            1e-12 * one.gradient.lpNorm<Eigen::Infinity>());
  ASSERT_EQ(one.tets.size(), two.tets.size());
  for (std::size_t k = 0; k < one.tets.size(); ++k)
    for (int i = 0; i < 12; ++i) {
      ASSERT_TRUE((one.tets[k].rotated[i] == two.tets[k].rotated[i]).all());
      ASSERT_TRUE((one.tets[k].q[i] == two.tets[k].q[i]).all());
    }
  for (std::size_t e = 0; e < model.tets.size(); ++e)
    ASSERT_EQ(one_state.tet_rotation[e].coeffs(), two_state.tet_rotation[e].coeffs());
}

}  // namespace
}  // namespace handlab::sim
