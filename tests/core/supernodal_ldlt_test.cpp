// The panel solve of a sparse LDL' factorisation (core/sim/supernodal_ldlt.h) on matrices with
// the simulator's structure: the study hand's TetGen mesh, 3x3 blocks per node pair of a tet,
// and the bones' 6 DOFs coupled to the nodes of the tets their coupling points lie in.
#include <cmath>
#include <initializer_list>
#include <random>

#include <gtest/gtest.h>

#include "core/sim/lanes.h"
#include "core/sim/supernodal_ldlt.h"
#include "tests/support/hand_like_matrix.h"

namespace handlab::sim {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using test::hand_like_matrix;
using test::study_flesh;

TEST(SupernodalLdlt, SolvesAsTheFactorisationItRearranges) {
  const Sparse a = hand_like_matrix(study_flesh(), 16, 1);
  SupernodalLdlt::Factor ldlt(a);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  SupernodalLdlt panels;
  panels.set(ldlt);
  // A node's three columns would make a third as many panels; relaxed amalgamation gathers
  // the small ones into their parents' far beyond that.
  EXPECT_LT(panels.supernodes(), a.cols() / 10) << "columns should gather into panels";
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd b(a.cols());
    for (double& v : b) v = normal(rng);
    const Eigen::VectorXd x = panels.solve(b), reference = ldlt.solve(b);
    EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
    EXPECT_LT((a * x - b).norm(), 1e-9 * b.norm());
  }
}

TEST(SupernodalLdlt, FollowsNewValuesAndNewPatterns) {
  const Sparse first = hand_like_matrix(study_flesh(), 16, 3);
  Sparse second = first;  // the same pattern, other values
  for (int k = 0; k < second.outerSize(); ++k)
    for (Sparse::InnerIterator it(second, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() *= 3.0;
  const Sparse third = hand_like_matrix(study_flesh(), 4, 5);  // another pattern
  SupernodalLdlt panels;
  SupernodalLdlt::Factor ldlt;
  ldlt.analyzePattern(first);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(first.cols(), -1.0, 1.0);
  for (const Sparse* a : std::initializer_list<const Sparse*>{&first, &second}) {
    ldlt.factorize(*a);
    panels.set(ldlt);
    EXPECT_LT((*a * panels.solve(b) - b).norm(), 1e-9 * b.norm());
  }
  ldlt.compute(third);
  panels.set(ldlt);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(third.cols(), -1.0, 1.0);
  EXPECT_LT((third * panels.solve(c) - c).norm(), 1e-9 * c.norm());
}

// Analysed once on Eigen's factorisation, it factorises other matrices of that pattern itself.
TEST(SupernodalLdlt, FactorisesMatricesOfTheAnalysedPattern) {
  const Sparse first = hand_like_matrix(study_flesh(), 16, 7);
  SupernodalLdlt::Factor ldlt(first);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  SupernodalLdlt panels;
  panels.analyze(ldlt, first);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> scale(0.5, 2.0);
  for (int trial = 0; trial < 3; ++trial) {
    // Same pattern, other values: each entry and its mirror scaled alike, the diagonal raised.
    Sparse a = first;
    for (int k = 0; k < a.outerSize(); ++k)
      for (Sparse::InnerIterator it(a, k); it; ++it) {
        const double f = 1.0 + 0.3 * std::sin(double(it.row() + it.col() + trial));
        it.valueRef() *= it.row() == it.col() ? 2.0 * scale(rng) : f;
      }
    ASSERT_TRUE(panels.factorize(a));
    const SupernodalLdlt::Factor reference(a);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.cols(), -1.0, 2.0);
    const Eigen::VectorXd x = panels.solve(b);
    EXPECT_LT((a * x - b).norm(), 1e-9 * b.norm()) << trial;
    EXPECT_LT((x - reference.solve(b)).norm(), 1e-9 * x.norm()) << trial;
  }
  const Sparse indefinite = -first;
  EXPECT_FALSE(panels.factorize(indefinite));
}

// Split over two lanes (the elimination tree's subtrees at once, then the supernodes above
// them), the factorisation solves as the serial one does, and gives the same factor bit for
// bit from call to call; an indefinite matrix is refused on either lane.
TEST(SupernodalLdlt, FactorisesOnTwoLanesAsOnOne) {
  const Sparse a = hand_like_matrix(study_flesh(), 16, 11);
  SupernodalLdlt::Factor ldlt(a);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  SupernodalLdlt serial, split;
  serial.analyze(ldlt, a);
  split.analyze(ldlt, a);
  ASSERT_TRUE(split.splits()) << "the hand's elimination tree has subtrees to deal out";
  Lanes lanes(2);
  ASSERT_TRUE(serial.factorize(a));
  ASSERT_TRUE(split.factorize(a, &lanes));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.cols(), -1.0, 2.0);
  const Eigen::VectorXd x = split.solve(b), reference = serial.solve(b);
  EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
  EXPECT_LT((a * x - b).norm(), 1e-9 * b.norm());
  for (int again = 0; again < 3; ++again) {
    ASSERT_TRUE(split.factorize(a, &lanes));
    ASSERT_EQ(split.solve(b), x) << "call " << again;
  }
  const Sparse indefinite = -a;
  EXPECT_FALSE(split.factorize(indefinite, &lanes));
}

}  // namespace
}  // namespace handlab::sim
