// The panel solve of a sparse LDL' factorisation (core/sim/supernodal_ldlt.h) on matrices with
// the simulator's structure: the study hand's TetGen mesh, 3x3 blocks per node pair of a tet,
// and the bones' 6 DOFs coupled to the nodes of the tets their coupling points lie in.
#include <cmath>
#include <initializer_list>
#include <random>

#include <gtest/gtest.h>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/sim/supernodal_ldlt.h"

namespace handlab::sim {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// A symmetric positive definite matrix over the flesh's nodes and the bones' DOFs: each tet
// adds a random positive semidefinite 12x12 block, each coupling point a spring between its
// tet's nodes and its bone, and the diagonal a mass.
Sparse hand_like_matrix(const hand::HandFlesh& flesh, int bones, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int nodes = int(flesh.tets.nodes.size()), dofs = 3 * nodes + 6 * bones;
  std::vector<Eigen::Triplet<double>> entries;
  auto add_gram = [&](const std::vector<int>& index, int rank) {
    Eigen::MatrixXd b(int(index.size()), rank);
    for (int i = 0; i < b.size(); ++i) b.data()[i] = unit(rng);
    const Eigen::MatrixXd block = b * b.transpose();
    for (int r = 0; r < block.rows(); ++r)
      for (int c = 0; c < block.cols(); ++c)
        entries.emplace_back(index[std::size_t(r)], index[std::size_t(c)], block(r, c));
  };
  for (const auto& tet : flesh.tets.tets) {
    std::vector<int> index;
    for (int node : tet)
      for (int k = 0; k < 3; ++k) index.push_back(3 * node + k);
    add_gram(index, 6);
  }
  for (const hand::CouplingPoint& p : flesh.coupling) {
    std::vector<int> index;
    for (int node : flesh.tets.tets[std::size_t(p.tet)])
      for (int k = 0; k < 3; ++k) index.push_back(3 * node + k);
    for (int k = 0; k < 6; ++k) index.push_back(3 * nodes + 6 * (p.bone % bones) + k);
    add_gram(index, 3);
  }
  for (int i = 0; i < dofs; ++i) entries.emplace_back(i, i, 1e-3);
  Sparse a(dofs, dofs);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

const hand::HandFlesh& study_flesh() {
  static const hand::HandFlesh flesh = [] {
    const hand::HandShape shape = hand::HandShape::with_length(0.214);
    return hand::build_flesh(hand::build_simulated_hand(shape), shape);
  }();
  return flesh;
}

TEST(SupernodalLdlt, SolvesAsTheFactorisationItRearranges) {
  const Sparse a = hand_like_matrix(study_flesh(), 16, 1);
  SupernodalLdlt::Factor ldlt(a);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  SupernodalLdlt panels;
  panels.set(ldlt);
  EXPECT_LT(panels.supernodes(), a.cols() / 3) << "columns should gather into panels";
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

}  // namespace
}  // namespace handlab::sim
