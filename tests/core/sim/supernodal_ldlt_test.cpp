// The panel solve of a sparse LDL' factorisation (core/sim/supernodal_ldlt.h) on matrices with
// the simulator's structure: the study hand's TetGen mesh, 3x3 blocks per node pair of a tet,
// and the bones' 6 DOFs coupled to the nodes of the tets their coupling points lie in.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/sim/supernodal_ldlt.h"
#include "core/sim/thread_pool.h"
#include "tests/support/hand_like_matrix.h"

namespace handlab::sim {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using test::hand_like_matrix;
using test::study_flesh;

// Panels analysed on Eigen's factorisation of `a` (the ordering and L's structure).
SupernodalLdlt analysed(const Sparse& a) {
  const SupernodalLdlt::Factor ldlt(a);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  SupernodalLdlt panels;
  panels.analyze(ldlt, a);
  return panels;
}

TEST(SupernodalLdlt, SolvesAsTheFactorizationItRearranges) {
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
TEST(SupernodalLdlt, FactorizesMatricesOfTheAnalysedPattern) {
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

// Split over two workers (the elimination tree's subtrees at once, then the supernodes above
// them, Geist & Ng's layer), the factorisation solves as the serial one does, and gives the
// same factor bit for bit from call to call; so does the solve split alike; an indefinite
// matrix is refused on either lane.
TEST(SupernodalLdlt, FactorizesOnTwoWorkersAsOnOne) {
  const Sparse a = hand_like_matrix(study_flesh(), 16, 11);
  SupernodalLdlt serial = analysed(a), split = analysed(a);
  ASSERT_TRUE(split.splits()) << "the hand's elimination tree has subtrees to deal out";
  ThreadPool pool(2);
  ASSERT_TRUE(serial.factorize(a));
  ASSERT_TRUE(split.factorize(a, &pool));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.cols(), -1.0, 2.0);
  const Eigen::VectorXd x = split.solve(b), reference = serial.solve(b);
  EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
  EXPECT_LT((a * x - b).norm(), 1e-9 * b.norm());
  for (int again = 0; again < 3; ++again) {
    ASSERT_TRUE(split.factorize(a, &pool));
    ASSERT_EQ(split.solve(b), x) << "call " << again;
  }
  // The solve on two workers too: the same answer to rounding, the same bits from call to call.
  const Eigen::VectorXd on_pool = split.solve(b, &pool);
  EXPECT_LT((on_pool - x).norm(), 1e-12 * x.norm());
  EXPECT_LT((a * on_pool - b).norm(), 1e-9 * b.norm());
  for (int again = 0; again < 3; ++again) ASSERT_EQ(split.solve(b, &pool), on_pool) << again;
  const Sparse indefinite = -a;
  EXPECT_FALSE(split.factorize(indefinite, &pool));
}

// The simulator writes its matrix into the panels itself: each entry of the lower triangle
// (after the ordering) at position(row, col), then factorize_values(). That gives the factor
// factorize() finds from the sparse matrix, bit for bit, and a node pair's 3x3 block lies in
// one panel, its entry (r, c) at position + r + stride c.
TEST(SupernodalLdlt, FactorizesWhatIsWrittenIntoItsPanels) {
  const Sparse first = hand_like_matrix(study_flesh(), 16, 5);
  SupernodalLdlt from_matrix = analysed(first), in_place = analysed(first);
  Sparse a = first;
  for (int k = 0; k < a.outerSize(); ++k)
    for (Sparse::InnerIterator it(a, k); it; ++it)
      it.valueRef() *= it.row() == it.col() ? 1.5 : 1.0 + 0.2 * std::cos(double(it.row() + k));
  in_place.clear_values();
  double* values = in_place.values();
  int written = 0;
  for (int k = 0; k < a.outerSize(); ++k)
    for (Sparse::InnerIterator it(a, k); it; ++it) {
      if (!in_place.ordered_after(int(it.row()), k)) continue;  // its mirror is written
      const int at = in_place.position(int(it.row()), k);
      ASSERT_GE(at, 0);
      values[at] += it.value();
      ++written;
    }
  EXPECT_EQ(written, (a.nonZeros() + a.cols()) / 2) << "each entry or its mirror, once";
  ASSERT_TRUE(in_place.factorize_values());
  ASSERT_TRUE(from_matrix.factorize(a));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.cols(), -1.0, 2.0);
  EXPECT_EQ(in_place.solve(b), from_matrix.solve(b));
  EXPECT_LT((a * in_place.solve(b) - b).norm(), 1e-9 * b.norm());
  // The blocks of the tets' node pairs, as the simulator writes them.
  int blocks = 0;
  for (const auto& tet : study_flesh().tets.tets)
    for (int i : tet)
      for (int j : tet) {
        if (!in_place.ordered_after(3 * i, 3 * j)) continue;
        const int at = in_place.position(3 * i, 3 * j), stride = in_place.column_stride(3 * j);
        for (int c = 0; c < 3; ++c)
          for (int r = i == j ? c : 0; r < 3; ++r)
            ASSERT_EQ(in_place.position(3 * i + r, 3 * j + c), at + r + stride * c);
        ++blocks;
      }
  EXPECT_GT(blocks, 10000);
}

// The ordering keeps a node's three unknowns together and in order, with no more fill than
// the ordering of the unknowns one by one; a size that is no multiple of 3 takes the latter.
TEST(BlockAmdOrdering, KeepsEachBlockTogetherWithoutMoreFill) {
  const Sparse a = hand_like_matrix(study_flesh(), 16, 3);
  BlockAmdOrdering::PermutationType perm;
  BlockAmdOrdering()(a, perm);
  ASSERT_EQ(perm.size(), a.cols());
  std::vector<bool> seen(std::size_t(a.cols()), false);
  for (int b = 0; b < a.cols() / 3; ++b) {
    const int first = perm.indices()[3 * b];
    ASSERT_EQ(first % 3, 0);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(perm.indices()[3 * b + k], first + k);
      seen[std::size_t(first + k)] = true;
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), a.cols()) << "a permutation";
  const SupernodalLdlt::Factor blocked(a);
  const Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> scalar(a);
  ASSERT_EQ(blocked.info(), Eigen::Success);
  ASSERT_EQ(scalar.info(), Eigen::Success);
  const auto fill = [](const auto& f) { return f.matrixL().nestedExpression().nonZeros(); };
  EXPECT_LT(double(fill(blocked)), 1.05 * double(fill(scalar)));
  const Sparse odd = a.topLeftCorner(a.cols() - 1, a.cols() - 1);
  BlockAmdOrdering()(odd, perm);
  EXPECT_EQ(perm.size(), odd.cols());
}

// The hand-like matrix with a body of 6 unknowns (the simulator's cube) coupled to many
// nodes: dense rows, which the ordering puts last.
Sparse with_body(const Sparse& a) {
  const int n = int(a.cols()), nodes = int(study_flesh().tets.nodes.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < a.outerSize(); ++k)
    for (Sparse::InnerIterator it(a, k); it; ++it)
      entries.emplace_back(int(it.row()), k, it.value());
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int node = 0; node < nodes; node += 3) {
    // A spring from the node to a point on the body: J = [I, -I, [arm]x], J'J on its blocks.
    const Eigen::Vector3d arm(unit(rng), unit(rng), unit(rng));
    Eigen::Matrix<double, 3, 9> j;
    j << Eigen::Matrix3d::Identity(), -Eigen::Matrix3d::Identity(),
        (Eigen::Matrix3d() << 0, -arm.z(), arm.y(), arm.z(), 0, -arm.x(), -arm.y(), arm.x(), 0)
            .finished();
    const Eigen::Matrix<double, 9, 9> block = j.transpose() * j;
    const auto index = [&](int i) { return i < 3 ? 3 * node + i : n + i - 3; };
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < 9; ++c) entries.emplace_back(index(r), index(c), block(r, c));
  }
  for (int r = 0; r < 6; ++r) entries.emplace_back(n + r, n + r, 1.0);
  Sparse out(n + 6, n + 6);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// Changing the trailing block (the last unknowns of the ordering) refactorises only it: the
// factor then solves A + E delta E'. Each call is relative to the matrix factorised; a change
// that leaves the matrix indefinite is refused and leaves the factor as it was.
TEST(SupernodalLdlt, ChangesItsTrailingBlockAlone) {
  const Sparse a = with_body(hand_like_matrix(study_flesh(), 16, 9));
  const int n = int(a.cols());
  SupernodalLdlt::Factor ldlt(a);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  std::vector<int> body;
  for (int k = 0; k < 6; ++k) {
    body.push_back(n - 6 + k);
    ASSERT_GE(ldlt.permutationP().indices()[n - 6 + k], n - 6) << "the body is ordered last";
  }
  SupernodalLdlt panels;
  panels.analyze(ldlt, a);
  ASSERT_TRUE(panels.trailing(body));
  EXPECT_FALSE(panels.trailing({0, 1, 2, 3, 4, 5}));
  EXPECT_FALSE(panels.trailing({n - 1, n - 1})) << "twice the same unknown";
  ASSERT_TRUE(panels.factorize(a));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd original = panels.solve(b);
  auto changed = [&](const Eigen::MatrixXd& delta) {
    Sparse c = a;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) c.coeffRef(n - 6 + i, n - 6 + j) += delta(i, j);
    return c;
  };
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::MatrixXd g(6, 6);
    for (double& v : g.reshaped()) v = normal(rng);
    const Eigen::MatrixXd delta = 50.0 * g * g.transpose() - 0.5 * Eigen::MatrixXd::Identity(6, 6);
    ASSERT_TRUE(panels.modify_trailing(body, delta)) << trial;
    const Sparse c = changed(delta);
    const Eigen::VectorXd x = panels.solve(b);
    EXPECT_LT((c * x - b).norm(), 1e-9 * b.norm()) << trial;
    EXPECT_LT((x - SupernodalLdlt::Factor(c).solve(b)).norm(), 1e-9 * x.norm()) << trial;
  }
  ASSERT_TRUE(panels.modify_trailing(body, Eigen::MatrixXd::Zero(6, 6)));
  EXPECT_LT((panels.solve(b) - original).norm(), 1e-12 * original.norm());
  const Eigen::MatrixXd before = panels.solve(b);
  EXPECT_FALSE(panels.modify_trailing(body, -1e6 * Eigen::MatrixXd::Identity(6, 6)));
  EXPECT_EQ(panels.solve(b), before) << "the factor unchanged";
  EXPECT_THROW(panels.modify_trailing({0, 1, 2, 3, 4, 5}, Eigen::MatrixXd::Zero(6, 6)),
               std::invalid_argument);
}

}  // namespace
}  // namespace handlab::sim
