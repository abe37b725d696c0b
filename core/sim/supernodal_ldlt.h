// Solves with a sparse LDL' factorisation rearranged into supernodes: runs of consecutive
// columns of L that share their rows below the run. Each run is stored as one dense panel, so
// that a solve applies small dense kernels to it and reads a row index once per panel row
// rather than once per nonzero. The simulator's preconditioner is applied several times a
// step and changes rarely: the panels are filled once per factorisation.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

namespace handlab::sim {

class SupernodalLdlt {
 public:
  using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

  // Takes the factor's values (and its structure, found again only when its pattern changed).
  void set(const Factor& factor);
  // b <- A^-1 b for the factorised A.
  void solve_in_place(Eigen::VectorXd& b) const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    Eigen::VectorXd x = b;
    solve_in_place(x);
    return x;
  }
  int supernodes() const { return int(nodes_.size()); }

 private:
  struct Supernode {
    int first = 0, width = 0;      // its columns (permuted order)
    int below = 0, row_begin = 0;  // rows under the diagonal block: rows_[row_begin, + below)
    int value_begin = 0;           // its (width + below) x width panel, column-major
  };
  void find_structure(const Eigen::SparseMatrix<double>& l);

  std::vector<Supernode> nodes_;
  std::vector<int> rows_;
  std::vector<double> values_;
  std::vector<int> column_to_panel_;  // values_ index of each column's first strict-lower entry
  Eigen::VectorXd inverse_diagonal_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p_, p_inverse_;
  std::vector<int> pattern_outer_;  // the structure the supernodes were found for
  std::vector<int> pattern_inner_;
  mutable Eigen::VectorXd work_, gathered_;
};

}  // namespace handlab::sim
