#include "core/sim/block_amd_ordering.h"

#include <vector>

namespace handlab::sim {

void BlockAmdOrdering::operator()(const Eigen::SparseMatrix<double>& a,
                                  PermutationType& perm) const {
  const int n = int(a.cols());
  Eigen::AMDOrdering<int> amd;
  if (n % kBlock != 0) {
    amd(a, perm);
    return;
  }
  const int blocks = n / kBlock;
  // The blocks' graph: blocks i and j adjacent where any of their entries is stored.
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(std::size_t(a.nonZeros()));
  for (int col = 0; col < n; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
      pattern.emplace_back(int(it.row()) / kBlock, col / kBlock, 1.0);
  Eigen::SparseMatrix<double> graph(blocks, blocks);
  graph.setFromTriplets(pattern.begin(), pattern.end());
  PermutationType block_perm;
  amd(graph, block_perm);
  perm.resize(n);
  for (int b = 0; b < blocks; ++b)
    for (int k = 0; k < kBlock; ++k)
      perm.indices()[kBlock * b + k] = kBlock * block_perm.indices()[b] + k;
}

}  // namespace handlab::sim
