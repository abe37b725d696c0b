// The linear solve (core/sim/linear_solve.h) on the Newton systems of the hand gripping the
// fine cube: its first solve factorises; a solve of the same matrix again uses the factor
// alone; a solve of a matrix found anew at a nearby state runs CG, preconditioned by the older
// factor. Each leaves no more residual than its tolerance per unknown, and says what it did.
#include <gtest/gtest.h>

#include "core/sim/hand_simulator.h"
#include "core/sim/linear_solve.h"
#include "core/sim/sim_options.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

double timed(const SimStepReport& report, StepTimer timer) {
  return report.timer_ms[std::size_t(timer)];
}

struct System {
  const HandSimModel& model;
  NewtonLayout layout;
  SolverMemory memory;
  ThreadPool pool{2};
  NewtonTerms terms;
  NewtonDiagonal diagonal_cache;

  explicit System(const HandSimModel& m) : model(m) {
    analyze_newton_matrix(model, memory, layout);
  }

  // Every term at the state, found anew (as a step's first evaluation).
  void evaluate(HandSimState s, const std::vector<RigidPose>& targets) {
    terms = test::empty_terms(model, true);
    diagonal_cache.known = false;
    ++memory.terms_found;
    test::add_every_term(model, s, targets, terms, &layout);
  }

  // A solve: the first of a new step, or the step's next.
  Eigen::VectorXd solve(const SimOptions& options, SimStepReport& report, bool new_step) {
    if (new_step) {
      ++memory.step;
      memory.solves_this_step = 0;
    }
    return solve_newton_step(model, terms, layout, diagonal_cache, options, pool, memory, report);
  }

  // The largest move the residual left would make of an unknown on its own.
  double left(const Eigen::VectorXd& x) {
    Eigen::VectorXd ax;
    multiply(model, terms, x, ax);
    NewtonDiagonal fresh;
    return ((-terms.gradient - ax).cwiseQuotient(diagonal(model, terms, fresh)))
        .lpNorm<Eigen::Infinity>();
  }
};

TEST(LinearSolve, FactorizesThenSolvesDirectlyThenByCg) {
  const test::GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  System system(model);
  const SimOptions options;
  system.evaluate(g.state, g.targets);

  SimStepReport first;
  const Eigen::VectorXd direct = system.solve(options, first, true);
  EXPECT_EQ(first.factorizations, 1) << "nothing factorised yet";
  EXPECT_EQ(first.direct_solves, 1);
  EXPECT_GT(direct.lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_LT(system.left(direct), 1e-3 * options.linear_tolerance);
  // Its time: the matrix written into the panels, factorised, solved; no CG.
  EXPECT_GT(timed(first, StepTimer::kAssemble), 0.0);
  EXPECT_GT(timed(first, StepTimer::kFactorize), 0.0);
  EXPECT_GT(timed(first, StepTimer::kDirectSolve), 0.0);
  EXPECT_EQ(timed(first, StepTimer::kCg), 0.0);
  EXPECT_EQ(first.failed_cg, 0) << "a factorisation for want of one is no failed CG";

  // The same matrix again (a later pass whose contacts did not change): the factor alone.
  SimStepReport again;
  const Eigen::VectorXd same = system.solve(options, again, false);
  EXPECT_EQ(again.factorizations, 0);
  EXPECT_EQ(again.direct_solves, 1);
  EXPECT_EQ(same, direct);
  EXPECT_EQ(timed(again, StepTimer::kAssemble), 0.0);
  EXPECT_EQ(timed(again, StepTimer::kFactorize), 0.0);
  EXPECT_GT(timed(again, StepTimer::kDirectSolve), 0.0);
  EXPECT_EQ(timed(again, StepTimer::kCg), 0.0);

  // The next step's matrix, a little way on: CG with the old factor as preconditioner.
  HandSimState next = g.state;
  std::vector<Eigen::Vector3d> turned(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
  test::move_by(model, next, turned, direct, 1.0);
  system.evaluate(next, g.targets);
  SimStepReport cg;
  const Eigen::VectorXd iterated = system.solve(options, cg, true);
  EXPECT_EQ(cg.factorizations, 0);
  EXPECT_EQ(cg.direct_solves, 0);
  EXPECT_EQ(cg.failed_cg, 0);
  EXPECT_GE(cg.linear_iterations, 1);
  EXPECT_LE(cg.linear_iterations, options.max_linear_iterations);
  EXPECT_LE(system.left(iterated), options.linear_tolerance);
  EXPECT_GT(timed(cg, StepTimer::kCg), 0.0);
  EXPECT_EQ(timed(cg, StepTimer::kAssemble) + timed(cg, StepTimer::kFactorize) +
                timed(cg, StepTimer::kDirectSolve),
            0.0);
}

// When CG cannot reach the tolerance in its iterations, the matrix is factorised and solved
// directly; and with the previous step's factor behind that failure, the next steps factorise
// at once.
TEST(LinearSolve, FallsBackToTheFactorizationWhenCgFails) {
  const test::GraspScene& g = test::gripping_fine_cube();
  const HandSimModel& model = g.scene.model;
  System system(model);
  SimOptions options;
  options.max_linear_iterations = 1;
  options.linear_tolerance = 1e-14;
  options.halfway_gap = 0;
  system.evaluate(g.state, g.targets);
  SimStepReport first;
  system.solve(options, first, true);
  ASSERT_EQ(first.factorizations, 1);

  HandSimState next = g.state;
  std::vector<Eigen::Vector3d> turned(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero());
  test::move_by(model, next, turned, test::direction(model, 1e-4, 1e-3), 1.0);
  system.evaluate(next, g.targets);
  SimStepReport failed;
  const Eigen::VectorXd x = system.solve(options, failed, true);
  EXPECT_EQ(failed.factorizations, 1);
  EXPECT_EQ(failed.direct_solves, 1);
  EXPECT_EQ(failed.linear_iterations, 2) << "one CG iteration, then the direct solve";
  EXPECT_EQ(failed.failed_cg, 1);
  for (StepTimer part :
       {StepTimer::kCg, StepTimer::kAssemble, StepTimer::kFactorize, StepTimer::kDirectSolve})
    EXPECT_GT(timed(failed, part), 0.0) << "each part of a failed CG's solve is timed";
  EXPECT_LT(system.left(x), 1e-3 * 1e-8);
  EXPECT_EQ(system.memory.direct_until, system.memory.step + 1 + options.direct_steps);
}

}  // namespace
}  // namespace handlab::sim
