// A sparse LDL' factorisation in supernodes: runs of consecutive columns of L that share their
// rows below the run, each stored as one dense panel. Factorising and solving then apply dense
// kernels to panels (a blocked Cholesky of each diagonal block, a triangular solve and a
// symmetric rank update below it) and read a row index once per panel row rather than once
// per nonzero. The structure (fill-reducing ordering and L's pattern) is taken from a
// factorisation by Eigen's SimplicialLDLT on the same pattern, ordered by BlockAmdOrdering; the
// simulator then writes its Newton matrix, whose pattern is fixed, into the panels directly
// (position, values) and factorises them there.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "core/sim/block_amd_ordering.h"

namespace handlab::sim {

class ThreadPool;

class SupernodalLdlt {
 public:
  using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, BlockAmdOrdering>;

  // Takes the factor's values (and its structure, found again only when its pattern changed).
  void set(const Factor& factor);
  // Takes the structure of `factor`, a factorisation of `a`, and learns where each of a's
  // stored entries goes, so that factorize() can take any matrix with a's pattern.
  void analyze(const Factor& factor, const Eigen::SparseMatrix<double>& a);
  // Factorises `a` (the analysed pattern) into the panels; false if it is not positive definite.
  // With a `pool` of two workers or more, the elimination tree's two largest groups of subtrees are
  // factorised on workers 0 and 1 at once, then the supernodes above them; the result depends
  // on whether a pool is given, never on timing.
  bool factorize(const Eigen::SparseMatrix<double>& a, ThreadPool* pool = nullptr);

  // Assembling in place, without the sparse matrix: clear_values(), then add each entry of the
  // matrix's lower triangle after the ordering at position(row, col) of values() (row and col
  // the matrix's own indices; A(row, col) and A(col, row) share the place), then
  // factorize_values(). position() is -1 outside L's structure; a 3x3 block of unknowns that
  // BlockAmdOrdering kept together lies at position(row, col) + r + column_stride(col) c.
  void clear_values();
  double* values() { return values_.data(); }
  int value_count() const { return int(values_.size()); }
  // The first value of the panel that holds `value` (panels lie in order in values()).
  int panel_start(int value) const;
  int position(int row, int col) const;
  int column_stride(int col) const;
  bool factorize_values(ThreadPool* pool = nullptr);
  // Whether the ordering puts `row` after `col` (A(row, col) is stored as itself, not as its
  // transpose).
  bool ordered_after(int row, int col) const { return permuted(row) >= permuted(col); }

  // Makes the factor that of A + E delta E' instead of A (the matrix last factorised), where E
  // selects the unknowns `dofs`: the ordering must have put them last, in the last supernode,
  // so that only the trailing block of L and D changes (the Schur complement S of those
  // columns becomes S + delta). Each call replaces the one before. False, with the factor
  // unchanged, if S + delta is not positive definite.
  bool modify_trailing(const std::vector<int>& dofs,
                       const Eigen::Ref<const Eigen::MatrixXd>& delta);
  // Whether modify_trailing takes these unknowns (the ordering put them last, in one panel).
  bool trailing(const std::vector<int>& dofs) const;

  // b <- A^-1 b for the factorised A. With a `pool` of two workers or more, the groups of subtrees
  // that factorize() splits are solved at once (the result depends on whether a pool is
  // given, never on timing).
  // Not const: the solve works in the object's own buffers (one solve at a time).
  void solve_in_place(Eigen::VectorXd& b, ThreadPool* pool = nullptr);
  Eigen::VectorXd solve(const Eigen::VectorXd& b, ThreadPool* pool = nullptr) {
    Eigen::VectorXd x = b;
    solve_in_place(x, pool);
    return x;
  }
  int supernodes() const { return int(nodes_.size()); }
  // Whether factorize() with a pool splits the work (analyze found subtrees to deal out).
  bool splits() const { return !top_.empty(); }
  // The work on the split's longer path (the top's flops and the larger group's) as a share
  // of a whole factorisation's: 1 unsplit, 1/2 at best.
  double split_critical_share() const { return split_critical_share_; }

 private:
  struct Supernode {
    int first = 0, width = 0;      // its columns (permuted order)
    int below = 0, row_begin = 0;  // rows under the diagonal block: rows_[row_begin, + below)
    int value_begin = 0;           // its (width + below) x width panel, column-major
  };
  void find_structure(const Eigen::SparseMatrix<double>& l);
  void plan_split();  // group_, top_ and their copies' offsets (see below)
  void choose_top(const std::vector<int>& parent, const std::vector<double>& work,
                  const std::vector<double>& subtree);
  void lay_out_top_copies();
  // Supernode s: its diagonal block, the rows below, its part of D, and its rank update to
  // later supernodes (through `scratch`); the update of a supernode of the top goes to `top`
  // (top_updates_'s layout) when given. False if the diagonal block is not positive definite.
  bool factorize_node(std::size_t s, Eigen::MatrixXd& scratch, double* top);
  // Supernode t's part of the forward and the backward solve on work_ (`gathered` a scratch
  // of the worker's; updates to rows of the top's columns into `top` when given).
  void forward(int t, Eigen::VectorXd& gathered, double* top);
  void backward(int t, Eigen::VectorXd& gathered);
  int permuted(int i) const { return p_.size() > 0 ? p_.indices()[i] : i; }
  // Position of (permuted) row `row` in supernode t's panel rows.
  int panel_row(int t, int row) const;

  // A run of supernode s's rows below its diagonal block whose columns belong to one later
  // supernode: the rank update's columns there go to that supernode's panel, rows
  // [begin, below) of s landing at relative_[relative_begin + i - begin].
  struct Update {
    int target = 0, begin = 0, end = 0, relative_begin = 0;
  };

  std::vector<Supernode> nodes_;
  std::vector<int> rows_;
  std::vector<double> values_;
  Eigen::VectorXd inverse_diagonal_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p_, p_inverse_;
  std::vector<int> pattern_outer_;  // the structure the supernodes were found for
  std::vector<int> pattern_inner_;
  Eigen::VectorXd work_, gathered_, gathered_second_, top_work_;  // the solves' buffers
  // For factorize(): each supernode's updates, the matrix's entries' panel positions (-1 for
  // the upper triangle), the owning supernode of each column.
  std::vector<int> update_begin_;  // updates_[update_begin_[s], update_begin_[s + 1])
  std::vector<Update> updates_;
  std::vector<int> relative_;
  std::vector<int> scatter_;
  std::vector<int> column_node_;
  int matrix_entries_ = -1;
  Eigen::MatrixXd rank_update_;
  // The split over two workers: the top (top_, ascending; group 2), closed upwards, and under
  // it whole subtrees in group 0 or 1 (group_). Group 1's updates to the top go into a copy
  // of its values (top_updates_, each top supernode's from top_value_offset_) and, in the
  // forward solve, of its columns (top_work_, from top_column_offset_), added before the top
  // is factorised or solved.
  std::vector<int> group_, top_, top_value_offset_, top_column_offset_;
  Eigen::VectorXd top_updates_;
  double split_critical_share_ = 1.0;
  Eigen::MatrixXd rank_update_second_;
  Eigen::VectorXd diagonal_;  // D, as factorize_node finds it
  // The trailing columns' Schur complement in the factor as factorised (modify_trailing), and
  // whether it is known.
  Eigen::MatrixXd trailing_schur_;
  bool trailing_known_ = false;
};

}  // namespace handlab::sim
