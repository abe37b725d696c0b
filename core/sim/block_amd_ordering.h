// Approximate minimum degree on a matrix of 3x3 blocks (a node's or a body's three unknowns):
// the ordering of the blocks' graph, each block's unknowns kept together and in order. The
// sparse factorisation then stores a block of the matrix as a 3x3 block of a panel, which the
// simulator's assembly writes with one index (SupernodalLdlt::position). Fill is as low as a
// scalar ordering's (docs/performance.md, "Simulator"). An Eigen ordering
// functor, for SimplicialLDLT's third parameter.
#pragma once

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

namespace handlab::sim {

class BlockAmdOrdering {
 public:
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  static constexpr int kBlock = 3;

  // `a` symmetric in pattern (SimplicialLDLT passes its full self-adjoint view). A matrix
  // whose size is not a multiple of 3 takes the scalar ordering.
  void operator()(const Eigen::SparseMatrix<double>& a, PermutationType& perm) const;
};

}  // namespace handlab::sim
