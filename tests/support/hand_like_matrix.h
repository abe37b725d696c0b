// A symmetric positive definite matrix with the simulator's structure, for the sparse
// factorisation's tests and benchmarks: the study hand's TetGen mesh, 3x3 blocks per node
// pair of a tet, and the bones' 6 DOFs coupled to the nodes of the tets their coupling points
// lie in.
#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"

namespace handlab::test {

using Sparse = Eigen::SparseMatrix<double>;

// A symmetric positive definite matrix over the flesh's nodes and the bones' DOFs: each tet
// adds a random positive semidefinite 12x12 block, each coupling point a spring between its
// tet's nodes and its bone, and the diagonal a mass.
inline Sparse hand_like_matrix(const hand::HandFlesh& flesh, int bones, unsigned seed) {
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

inline const hand::HandFlesh& study_flesh() {
  static const hand::HandFlesh flesh = [] {
    const hand::HandShape shape = hand::HandShape::with_length(0.214);
    return hand::build_flesh(hand::build_simulated_hand(shape), shape);
  }();
  return flesh;
}

}  // namespace handlab::test
