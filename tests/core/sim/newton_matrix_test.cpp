// The Newton matrix held as its terms (core/sim/newton_matrix.h), at states of the scripted
// pinch (approach, closing, grip, lift): every energy's terms as a step finds them; the
// term-by-term product and diagonal that CG uses, and the matrix written into the
// factorisation's panels, against the matrix assembled entry by entry from the same terms.
#include <gtest/gtest.h>

#include "core/sim/linear_solve.h"
#include "core/sim/newton_matrix.h"
#include "core/sim/thread_pool.h"
#include "tests/core/sim/stage_fixture.h"

namespace handlab::sim {
namespace {

struct Evaluated {
  const test::GraspScene& grasp;
  NewtonTerms terms;
};

// Every term of a step's first evaluation at the pinch's stage at `time`; `layout`, when given,
// the fixed springs' places in the panels (as the engine passes them).
Evaluated evaluated(double time, const NewtonLayout* layout = nullptr) {
  Evaluated e{test::pinch_stage(time), {}};
  const HandSimModel& model = e.grasp.scene.model;
  HandSimState s = e.grasp.state;
  e.terms = test::empty_terms(model, true);
  test::add_every_term(model, s, e.grasp.targets, e.terms, layout);
  return e;
}

TEST(NewtonMatrixAtPinchStages, ProductAndDiagonalEqualTheAssembledMatrix) {
  ThreadPool pool(2);
  for (double stage : test::kPinchStages) {
    SCOPED_TRACE(stage);
    const Evaluated e = evaluated(stage);
    const HandSimModel& model = e.grasp.scene.model;
    const Eigen::SparseMatrix<double> a = test::assembled(model, e.terms);
    const Eigen::SparseMatrix<double> magnitude = a.cwiseAbs();
    for (double phase : {1.0, 2.0, 3.0}) {
      const Eigen::VectorXd x = test::direction(model, 1.0, 1.0, phase);
      Eigen::VectorXd y, split, scratch;
      multiply(model, e.terms, x, y);
      // Rounding scales with the terms summed, |A| |x|, not with the (cancelling) result.
      const Eigen::VectorXd bound = 1e-12 * (magnitude * x.cwiseAbs());
      EXPECT_TRUE(((y - a * x).cwiseAbs().array() <= bound.array()).all()) << "phase " << phase;
      // Split between two workers: the same product to rounding, the same bits call to call.
      multiply(model, e.terms, x, split, &pool, &scratch);
      EXPECT_TRUE(((split - a * x).cwiseAbs().array() <= bound.array()).all()) << "phase " << phase;
      Eigen::VectorXd again;
      multiply(model, e.terms, x, again, &pool, &scratch);
      EXPECT_EQ(again, split);
    }
    NewtonDiagonal cache;
    const Eigen::VectorXd diagonal_found = diagonal(model, e.terms, cache);
    EXPECT_TRUE(cache.known);
    EXPECT_LT((diagonal_found - a.diagonal()).lpNorm<Eigen::Infinity>(),
              1e-12 * a.diagonal().lpNorm<Eigen::Infinity>());
    // The kept part found once: the same diagonal again from the cache.
    EXPECT_EQ(diagonal(model, e.terms, cache), diagonal_found);
  }
}

TEST(NewtonMatrixAtPinchStages, PanelsHoldTheAssembledMatrix) {
  // One model for every stage: its panels' layout is analysed once, as the engine does.
  SolverMemory memory;
  NewtonLayout layout;
  analyze_newton_matrix(test::pinch_stage(test::kPinchStages.front()).scene.model, memory, layout);
  for (double stage : test::kPinchStages) {
    SCOPED_TRACE(stage);
    const Evaluated e = evaluated(stage, &layout);
    const HandSimModel& model = e.grasp.scene.model;
    const Eigen::SparseMatrix<double> a = test::assembled(model, e.terms);
    const SupernodalLdlt& factor = memory.factor;
    std::vector<double> panels(std::size_t(factor.value_count()), 0.0);
    write_panels(model, e.terms, layout, factor, panels.data());
    // Entry by entry, rounding on the scale of the entry's row and column (|A_rc| <=
    // sqrt(A_rr A_cc), and an entry summed to nearly zero keeps its terms' rounding); the lower
    // triangle after the ordering holds them all.
    const Eigen::VectorXd diag = a.diagonal();
    int compared = 0, without_place = 0;
    for (int col = 0; col < a.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it) {
        if (!factor.ordered_after(int(it.row()), col)) continue;
        const int at = factor.position(int(it.row()), col);
        if (at < 0) {
          ++without_place;
          continue;
        }
        EXPECT_LE(std::abs(panels[std::size_t(at)] - it.value()),
                  1e-12 * std::sqrt(diag[it.row()] * diag[col]))
            << it.row() << ", " << col;
        ++compared;
      }
    EXPECT_EQ(without_place, 0);  // every entry of the lower triangle has its place in a panel
    EXPECT_GT(compared, 50000);
    // Split between two workers, the same sums bit for bit.
    std::vector<double> split(panels.size(), 0.0);
    write_panels(model, e.terms, layout, factor, split.data(), 0);
    write_panels(model, e.terms, layout, factor, split.data(), 1);
    EXPECT_EQ(split, panels);
  }
}

// The study hand's factorisation splits over two workers with the work nearly halved: the
// heaviest subtrees are split under a top that need not be a tail of the supernodes (a tail
// left 0.79 of the work on the longer worker's path).
TEST(NewtonMatrixAtPinchStages, TwoWorkersShareTheFactorisation) {
  SolverMemory memory;
  NewtonLayout layout;
  analyze_newton_matrix(test::pinch_stage(test::kPinchStages.front()).scene.model, memory, layout);
  ASSERT_TRUE(memory.factor.splits());
  EXPECT_LT(memory.factor.split_critical_share(), 0.62);
}

// The cube's own terms: its inertia and the floor's contacts with its corners.
TEST(NewtonMatrixAtPinchStages, CubeMatrixIsTheCubesOwnTerms) {
  for (double stage : test::kPinchStages) {
    SCOPED_TRACE(stage);
    const Evaluated e = evaluated(stage);
    const HandSimModel& model = e.grasp.scene.model;
    NewtonTerms own = e.terms;
    own.tets.clear();
    own.springs.clear();
    for (std::size_t i = e.terms.first_contact_spring; i < e.terms.springs.size(); ++i) {
      const SpringTerm& t = e.terms.springs[i];
      bool alone = true;
      for (int k = 0; k < t.p.count; ++k)
        alone = alone && t.p.block[std::size_t(k)] >= cube_block(model);
      if (alone) own.springs.push_back(t);
    }
    own.blocks.clear();
    for (const BlockTerm& t : e.terms.blocks)
      if (t.block >= cube_block(model)) own.blocks.push_back(t);
    const Eigen::MatrixXd a =
        Eigen::MatrixXd(test::assembled(model, own, false)).bottomRightCorner(6, 6);
    EXPECT_LT((cube_matrix(model, e.terms) - a).lpNorm<Eigen::Infinity>(),
              1e-12 * a.lpNorm<Eigen::Infinity>());
    // Contacts on other unknowns are found again bit for bit, and a change is seen.
    std::vector<SpringTerm> others;
    other_contacts(model, e.terms, others);
    EXPECT_TRUE(same_other_contacts(model, e.terms, others));
    if (!others.empty()) {
      others.back().k *= 1.0 + 1e-15;
      EXPECT_FALSE(same_other_contacts(model, e.terms, others));
    }
  }
}

// The whole cube-cube block, the flesh's contacts with it too: the cube's Newton matrix when the
// flesh is held (linear_solve.h, solve_cube_step).
TEST(NewtonMatrixAtPinchStages, CubeBlockMatrixIsTheMatrixsCubeBlock) {
  for (double stage : test::kPinchStages) {
    SCOPED_TRACE(stage);
    const Evaluated e = evaluated(stage);
    const HandSimModel& model = e.grasp.scene.model;
    const Eigen::MatrixXd a =
        Eigen::MatrixXd(test::assembled(model, e.terms, false)).bottomRightCorner(6, 6);
    EXPECT_LT((cube_block_matrix(model, e.terms) - a).lpNorm<Eigen::Infinity>(),
              1e-12 * a.lpNorm<Eigen::Infinity>());
    if (stage >= 1.2) {  // the pads on the cube: more than its own terms
      EXPECT_GT((a - cube_matrix(model, e.terms)).lpNorm<Eigen::Infinity>(),
                1e-3 * a.lpNorm<Eigen::Infinity>());
    }
  }
}

}  // namespace
}  // namespace handlab::sim
