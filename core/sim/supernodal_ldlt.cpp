#include "core/sim/supernodal_ldlt.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "core/sim/thread_pool.h"

namespace handlab::sim {

namespace {

// Entries of a supernode's lower trapezoid: its diagonal block's lower triangle and the rows
// below it.
long trapezoid(long width, long below) {
  return width * (width + 1) / 2 + width * below;
}

// The largest panel (values) factorised column by column (factorize_node): 64 kB, which
// stays in the fast caches while each column reads the ones before it.
constexpr int kColumnByColumn = 8192;

// Whether a supernode of `width` columns whose panel would hold `zeros` of its `entries` as
// explicit zeros is worth its denser kernels: CHOLMOD's relaxed amalgamation rule and
// defaults (any merge up to 4 columns, up to 80% zeros up to 16 columns, 10% up to 48, 5%
// beyond).
bool worth_merging(long width, long zeros, long entries) {
  const double z = double(zeros) / double(entries);
  if (width <= 4) return true;
  if (width <= 16) return z < 0.8;
  if (width <= 48) return z < 0.1;
  return z < 0.05;
}

}  // namespace

void SupernodalLdlt::find_structure(const Eigen::SparseMatrix<double>& l) {
  const int n = int(l.cols());
  const int* outer = l.outerIndexPtr();
  const int* inner = l.innerIndexPtr();
  auto count = [&](int j) { return outer[j + 1] - outer[j]; };
  // Fundamental supernodes: column j + 1 continues j's when j's rows are j + 1 followed by
  // exactly j + 1's.
  auto continues = [&](int j) {
    return count(j) == count(j + 1) + 1 && inner[outer[j]] == j + 1 &&
           std::equal(inner + outer[j] + 1, inner + outer[j + 1], inner + outer[j + 1]);
  };
  // Relaxed amalgamation: a supernode whose parent (the supernode of its first row below)
  // starts right after it merges into it when the explicit zeros that adds are few (its
  // columns then take the parent's rows); the many two- and three-column supernodes of a
  // tet mesh become panels wide enough for the dense kernels to pay. The elimination tree
  // guarantees a child's rows below lie within its parent's columns and rows.
  struct Run {
    int first = 0, width = 0, last = 0;  // columns; `last` the column whose rows it has below
    long entries = 0;                    // structural nonzeros of L in it (its columns')
  };
  std::vector<Run> runs;
  for (int j = 0; j < n;) {
    Run f;
    f.first = j;
    f.width = 1;
    while (j + f.width < n && continues(j + f.width - 1)) ++f.width;
    f.last = j + f.width - 1;
    f.entries = trapezoid(f.width, count(f.last));
    j += f.width;
    if (!runs.empty()) {
      const Run& c = runs.back();
      const bool parent = count(c.last) > 0 && inner[outer[c.last]] <= f.last;
      const long width = c.width + f.width, merged = trapezoid(width, count(f.last));
      if (parent && worth_merging(width, merged - c.entries - f.entries, merged)) {
        runs.back() = {c.first, int(width), f.last, c.entries + f.entries};
        continue;
      }
    }
    runs.push_back(f);
  }
  nodes_.clear();
  rows_.clear();
  int values = 0;
  for (const Run& r : runs) {
    Supernode s;
    s.first = r.first;
    s.width = r.width;
    s.below = count(r.last);
    s.row_begin = int(rows_.size());
    rows_.insert(rows_.end(), inner + outer[r.last], inner + outer[r.last + 1]);
    s.value_begin = values;
    values += (s.width + s.below) * s.width;
    nodes_.push_back(s);
  }
  // The diagonal blocks' unit diagonal and zero upper parts stay; set() fills the rest.
  values_.assign(std::size_t(values), 0.0);
  for (const Supernode& s : nodes_)
    for (int c = 0; c < s.width; ++c)
      values_[std::size_t(s.value_begin + c * (s.width + s.below) + c)] = 1.0;
  column_node_.assign(std::size_t(n), 0);
  for (std::size_t t = 0; t < nodes_.size(); ++t)
    for (int c = 0; c < nodes_[t].width; ++c)
      column_node_[std::size_t(nodes_[t].first + c)] = int(t);
  gathered_.resize(n);
  gathered_second_.resize(n);
  // A new structure: factorize() waits for analyze() to map a matrix and plan the split.
  matrix_entries_ = -1;
  top_.clear();
  split_critical_share_ = 1.0;
  pattern_outer_.assign(outer, outer + n + 1);
  pattern_inner_.assign(inner, inner + outer[n]);
}

void SupernodalLdlt::set(const Factor& factor) {
  if (factor.info() != Eigen::Success)
    throw std::invalid_argument("SupernodalLdlt: the factorisation failed");
  const Eigen::SparseMatrix<double>& l = factor.matrixL().nestedExpression();
  if (!l.isCompressed()) throw std::invalid_argument("SupernodalLdlt: L is not compressed");
  const int n = int(l.cols());
  const int* outer = l.outerIndexPtr();
  const int* inner = l.innerIndexPtr();
  if (int(pattern_outer_.size()) != n + 1 ||
      !std::equal(outer, outer + n + 1, pattern_outer_.begin()) ||
      !std::equal(inner, inner + outer[n], pattern_inner_.begin()))
    find_structure(l);
  const double* lx = l.valuePtr();
  for (int j = 0; j < n; ++j) {
    const int t = column_node_[std::size_t(j)];
    const Supernode& s = nodes_[std::size_t(t)];
    double* column = values_.data() + s.value_begin + (j - s.first) * (s.width + s.below);
    for (int v = outer[j]; v < outer[j + 1]; ++v) column[panel_row(t, inner[v])] = lx[v];
  }
  inverse_diagonal_ = factor.vectorD().cwiseInverse();
  trailing_known_ = false;
  p_ = factor.permutationP();
  p_inverse_ = factor.permutationPinv();
}

int SupernodalLdlt::panel_row(int t, int row) const {
  const Supernode& s = nodes_[std::size_t(t)];
  if (row >= s.first && row < s.first + s.width) return row - s.first;
  const auto begin = rows_.begin() + s.row_begin, end = begin + s.below;
  const auto it = std::lower_bound(begin, end, row);
  return it != end && *it == row ? s.width + int(it - begin) : -1;
}

int SupernodalLdlt::position(int row, int col) const {
  int r = permuted(row), c = permuted(col);
  if (r < c) std::swap(r, c);
  const int t = column_node_[std::size_t(c)];
  const Supernode& node = nodes_[std::size_t(t)];
  const int in_panel = panel_row(t, r);
  return in_panel < 0 ? -1
                      : node.value_begin + (c - node.first) * (node.width + node.below) + in_panel;
}

int SupernodalLdlt::panel_start(int value) const {
  const auto after = std::upper_bound(nodes_.begin(), nodes_.end(), value,
                                      [](int v, const Supernode& s) { return v < s.value_begin; });
  return after == nodes_.begin() ? 0 : std::prev(after)->value_begin;
}

int SupernodalLdlt::column_stride(int col) const {
  const Supernode& node = nodes_[std::size_t(column_node_[std::size_t(permuted(col))])];
  return node.width + node.below;
}

void SupernodalLdlt::clear_values() {
  std::fill(values_.begin(), values_.end(), 0.0);
}

void SupernodalLdlt::analyze(const Factor& factor, const Eigen::SparseMatrix<double>& a) {
  if (!a.isCompressed()) throw std::invalid_argument("SupernodalLdlt: compress the matrix");
  set(factor);
  const int n = int(a.cols());
  // Each supernode's rank update, split by the supernodes that own its columns.
  update_begin_.assign(nodes_.size() + 1, 0);
  updates_.clear();
  relative_.clear();
  int widest = 0;
  for (std::size_t s = 0; s < nodes_.size(); ++s) {
    const Supernode& node = nodes_[s];
    widest = std::max(widest, node.below);
    const int* rows = rows_.data() + node.row_begin;
    for (int j = 0; j < node.below;) {
      Update u;
      u.target = column_node_[std::size_t(rows[j])];
      u.begin = j;
      u.end = j + 1;
      while (u.end < node.below && column_node_[std::size_t(rows[u.end])] == u.target) ++u.end;
      u.relative_begin = int(relative_.size());
      for (int i = j; i < node.below; ++i) {
        const int r = panel_row(u.target, rows[i]);
        if (r < 0) throw std::logic_error("SupernodalLdlt: a row outside its target's structure");
        relative_.push_back(r);
      }
      updates_.push_back(u);
      j = u.end;
    }
    update_begin_[s + 1] = int(updates_.size());
  }
  rank_update_.resize(widest, widest);
  // Where each stored entry of the lower triangle (after the ordering) goes.
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const int* order = p_.indices().data();
  scatter_.assign(std::size_t(a.nonZeros()), -1);
  for (int col = 0; col < n; ++col)
    for (int v = outer[col]; v < outer[col + 1]; ++v) {
      const int pr = order[inner[v]], pc = order[col];
      if (pr < pc) continue;
      const int t = column_node_[std::size_t(pc)];
      const Supernode& node = nodes_[std::size_t(t)];
      const int r = panel_row(t, pr);
      if (r < 0) throw std::logic_error("SupernodalLdlt: an entry outside L's structure");
      scatter_[std::size_t(v)] =
          node.value_begin + (pc - node.first) * (node.width + node.below) + r;
    }
  matrix_entries_ = int(a.nonZeros());
  rank_update_second_.resize(widest, widest);
  plan_split();
}

void SupernodalLdlt::plan_split() {
  const int count = int(nodes_.size());
  // Each supernode's parent (the supernode of its first row below) and its work (flops of its
  // Cholesky, triangular solve and rank update), and each subtree's.
  std::vector<int> parent(static_cast<std::size_t>(count), -1);
  std::vector<double> work(static_cast<std::size_t>(count)), subtree(work.size());
  for (int t = 0; t < count; ++t) {
    const Supernode& n = nodes_[std::size_t(t)];
    if (n.below > 0)
      parent[std::size_t(t)] = column_node_[std::size_t(rows_[std::size_t(n.row_begin)])];
    const double w = n.width, b = n.below;
    work[std::size_t(t)] = w * w * w / 3 + w * w * b + w * b * b;
    subtree[std::size_t(t)] += work[std::size_t(t)];
    if (parent[std::size_t(t)] >= 0)
      subtree[std::size_t(parent[std::size_t(t)])] += subtree[std::size_t(t)];
  }
  choose_top(parent, work, subtree);
  lay_out_top_copies();
}

void SupernodalLdlt::choose_top(const std::vector<int>& parent, const std::vector<double>& work,
                                const std::vector<double>& subtree) {
  // The top: the supernodes factorised after the two groups, closed upwards (with a supernode,
  // its parent). Starting from the roots, the root supernode of the heaviest subtree under the
  // top is moved into it, one at a time, its children then dealt with the other subtrees
  // (Geist & Ng 1989, "Task scheduling for parallel sparse Cholesky factorization", Int J
  // Parallel Prog 18:291); the subtrees under it go to two groups, largest first. The top kept
  // is the one of least time: its work, then the larger group's.
  const int count = int(nodes_.size());
  std::vector<std::vector<int>> children(static_cast<std::size_t>(count));
  std::vector<int> roots;
  for (int t = 0; t < count; ++t)
    (parent[std::size_t(t)] >= 0 ? children[std::size_t(parent[std::size_t(t)])] : roots)
        .push_back(t);
  // Ties broken by index: the same plan with every standard library.
  auto heavier = [&](int a, int b) {
    return subtree[std::size_t(a)] != subtree[std::size_t(b)]
               ? subtree[std::size_t(a)] > subtree[std::size_t(b)]
               : a < b;
  };
  std::vector<int> top, best_top, best_group;
  std::vector<bool> in_top(std::size_t(count), false);
  double total = 0.0, top_flops = 0.0;
  for (int t = 0; t < count; ++t) total += work[std::size_t(t)];
  double best = total;
  while (!roots.empty()) {
    std::sort(roots.begin(), roots.end(), heavier);
    double load[2] = {0.0, 0.0};
    std::vector<int> group(std::size_t(count), 2);
    for (int r : roots) {
      const int g = load[1] < load[0] ? 1 : 0;
      load[g] += subtree[std::size_t(r)];
      group[std::size_t(r)] = g;
    }
    const double time = top_flops + std::max(load[0], load[1]);
    if (!top.empty() && time < best) {
      best = time;
      best_top = top;
      // Each supernode in its root's group: parents come later, so go down from the end.
      for (int t = count - 1; t >= 0; --t)
        if (group[std::size_t(t)] == 2 && !in_top[std::size_t(t)])
          group[std::size_t(t)] = group[std::size_t(parent[std::size_t(t)])];
      best_group = group;
    }
    const int heaviest = roots.front();
    roots.erase(roots.begin());
    top.push_back(heaviest);
    in_top[std::size_t(heaviest)] = true;
    top_flops += work[std::size_t(heaviest)];
    roots.insert(roots.end(), children[std::size_t(heaviest)].begin(),
                 children[std::size_t(heaviest)].end());
  }
  // Split only where it pays for the workers' hand-over and copies: a tenth off at least.
  if (best > 0.9 * total) {
    best = total;
    best_top.clear();
  }
  std::sort(best_top.begin(), best_top.end());
  top_ = best_top;
  split_critical_share_ = total > 0.0 ? best / total : 1.0;
  group_ = best_top.empty() ? std::vector<int>(std::size_t(count), 0) : best_group;
}

void SupernodalLdlt::lay_out_top_copies() {
  // Where the second group's updates to the top go: each top supernode's values, and each of
  // its columns, in a compact copy.
  top_value_offset_.assign(nodes_.size(), -1);
  top_column_offset_.assign(column_node_.size(), -1);
  int values = 0, columns = 0;
  for (int t : top_) {
    const Supernode& n = nodes_[std::size_t(t)];
    top_value_offset_[std::size_t(t)] = values;
    values += n.width * (n.width + n.below);
    for (int c = 0; c < n.width; ++c) top_column_offset_[std::size_t(n.first + c)] = columns++;
  }
  top_updates_ = Eigen::VectorXd::Zero(values);
  top_work_ = Eigen::VectorXd::Zero(columns);
}

bool SupernodalLdlt::factorize(const Eigen::SparseMatrix<double>& a, ThreadPool* pool) {
  if (int(a.nonZeros()) != matrix_entries_ || !a.isCompressed())
    throw std::invalid_argument("SupernodalLdlt: factorize a matrix of the analysed pattern");
  clear_values();
  const double* av = a.valuePtr();
  for (std::size_t v = 0; v < scatter_.size(); ++v)
    if (scatter_[v] >= 0) values_[std::size_t(scatter_[v])] += av[v];
  return factorize_values(pool);
}

bool SupernodalLdlt::factorize_values(ThreadPool* pool) {
  diagonal_.resize(inverse_diagonal_.size());
  const int count = int(nodes_.size());
  if (pool && pool->workers() >= 2 && splits()) {
    bool definite[2] = {true, true};
    // Worker 0 updates the top's panels in place, worker 1 into their copy, added afterwards.
    pool->run([&](int worker) {
      if (worker > 1) return;
      double* top = nullptr;
      if (worker == 1) {
        top_updates_.setZero();
        top = top_updates_.data();
      }
      Eigen::MatrixXd& scratch = worker == 0 ? rank_update_ : rank_update_second_;
      for (int t = 0; t < count && definite[worker]; ++t)
        if (group_[std::size_t(t)] == worker)
          definite[worker] = factorize_node(std::size_t(t), scratch, top);
    });
    if (!definite[0] || !definite[1]) return false;
    for (int t : top_) {
      const Supernode& n = nodes_[std::size_t(t)];
      Eigen::Map<Eigen::VectorXd>(values_.data() + n.value_begin, n.width * (n.width + n.below)) +=
          top_updates_.segment(top_value_offset_[std::size_t(t)], n.width * (n.width + n.below));
    }
    for (int t : top_)
      if (!factorize_node(std::size_t(t), rank_update_, nullptr)) return false;
  } else {
    for (int t = 0; t < count; ++t)
      if (!factorize_node(std::size_t(t), rank_update_, nullptr)) return false;
  }
  inverse_diagonal_ = diagonal_.cwiseInverse();
  trailing_known_ = false;
  return true;
}

bool SupernodalLdlt::trailing(const std::vector<int>& dofs) const {
  const int n = int(column_node_.size()), k = int(dofs.size());
  if (nodes_.empty() || k > nodes_.back().width) return false;
  std::vector<bool> taken(static_cast<std::size_t>(k), false);
  for (int dof : dofs) {
    if (dof < 0 || dof >= n) return false;
    const int at = permuted(dof) - (n - k);
    if (at < 0 || taken[std::size_t(at)]) return false;
    taken[std::size_t(at)] = true;
  }
  return true;
}

bool SupernodalLdlt::modify_trailing(const std::vector<int>& dofs,
                                     const Eigen::Ref<const Eigen::MatrixXd>& delta) {
  const int n = int(column_node_.size()), k = int(dofs.size());
  if (!trailing(dofs) || delta.rows() != k || delta.cols() != k)
    throw std::invalid_argument(
        "SupernodalLdlt::modify_trailing: the last unknowns of the ordering and a k x k change");
  const Supernode& last = nodes_.back();
  std::vector<int> at(static_cast<std::size_t>(k));  // each unknown's place in the block
  for (int i = 0; i < k; ++i) at[std::size_t(i)] = permuted(dofs[std::size_t(i)]) - (n - k);
  Eigen::Map<Eigen::MatrixXd> panel(values_.data() + last.value_begin, last.width, last.width);
  auto block = panel.bottomRightCorner(k, k);
  if (!trailing_known_) {
    // A = L D L' gives the trailing block's Schur complement as L22 D2 L22'.
    const Eigen::MatrixXd l = block.triangularView<Eigen::UnitLower>();
    const Eigen::VectorXd d = inverse_diagonal_.tail(k).cwiseInverse();
    trailing_schur_ = l * d.asDiagonal() * l.transpose();
    trailing_known_ = true;
  }
  Eigen::MatrixXd s = trailing_schur_;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) s(at[std::size_t(i)], at[std::size_t(j)]) += delta(i, j);
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd l = llt.matrixL();
  for (int c = 0; c < k; ++c) {
    const double root = l(c, c);
    inverse_diagonal_[n - k + c] = 1.0 / (root * root);
    block.col(c).tail(k - c - 1) = l.col(c).tail(k - c - 1) / root;
  }
  return true;
}

bool SupernodalLdlt::factorize_node(std::size_t s, Eigen::MatrixXd& scratch, double* top) {
  const Supernode& node = nodes_[s];
  const int height = node.width + node.below;
  Eigen::Map<Eigen::MatrixXd> panel(values_.data() + node.value_begin, height, node.width);
  // The diagonal block's Cholesky factor L_d and the rows below, L_b = A_b L_d^-T. A small
  // panel goes column by column (left-looking: a column takes the earlier columns' part as
  // one matrix-vector product, then its pivot's root), which beats a blocked Cholesky and a
  // triangular solve that pack their operands; a larger one, whose columns' products would
  // stream it from memory again and again, takes those.
  const bool by_column = height * node.width <= kColumnByColumn;
  if (!by_column) {
    auto block = panel.topRows(node.width);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(block);
    if (llt.info() != Eigen::Success) return false;
    if (node.below > 0)
      block.triangularView<Eigen::Lower>().solveInPlace(panel.bottomRows(node.below).transpose());
  }
  for (int c = 0; c < node.width && by_column; ++c) {
    auto column = panel.col(c).tail(height - c);
    if (c > 0)
      column.noalias() -= panel.bottomLeftCorner(height - c, c) * panel.row(c).head(c).transpose();
    const double pivot = column[0];
    if (!(pivot > 0.0)) return false;
    const double root = std::sqrt(pivot);
    column[0] = root;
    column.tail(height - c - 1) *= 1.0 / root;
  }
  if (node.below > 0) {
    auto below = panel.bottomRows(node.below);
    // Its rank update L_b L_b' (lower half) to the later supernodes that own its rows.
    auto update = scratch.topLeftCorner(node.below, node.below);
    update.triangularView<Eigen::Lower>().setZero();
    update.selfadjointView<Eigen::Lower>().rankUpdate(below);
    const int* rows = rows_.data() + node.row_begin;
    for (int k = update_begin_[s]; k < update_begin_[s + 1]; ++k) {
      const Update& u = updates_[std::size_t(k)];
      const Supernode& target = nodes_[std::size_t(u.target)];
      const int target_height = target.width + target.below;
      const int* relative = relative_.data() + u.relative_begin;  // of rows u.begin, ...
      const int in_top = top ? top_value_offset_[std::size_t(u.target)] : -1;
      double* destination = in_top >= 0 ? top + in_top : values_.data() + target.value_begin;
      for (int j = u.begin; j < u.end; ++j) {
        double* column = destination + (rows[j] - target.first) * target_height;
        const double* source = update.col(j).data();
        for (int i = j; i < node.below; ++i) column[relative[i - u.begin]] -= source[i];
      }
    }
  }
  // L L' = L_unit D L_unit': D the squared diagonal, the columns divided by it.
  for (int c = 0; c < node.width; ++c) {
    const double l = panel(c, c);
    diagonal_[node.first + c] = l * l;
    panel.col(c).tail(height - c - 1) /= l;
    panel(c, c) = 1.0;
  }
  return true;
}

void SupernodalLdlt::forward(int t, Eigen::VectorXd& gathered, double* top) {
  const Supernode& s = nodes_[std::size_t(t)];
  const Eigen::Map<const Eigen::MatrixXd> panel(values_.data() + s.value_begin, s.width + s.below,
                                                s.width);
  auto x = work_.segment(s.first, s.width);
  panel.topRows(s.width).triangularView<Eigen::UnitLower>().solveInPlace(x);
  if (s.below == 0) return;
  auto update = gathered.head(s.below);
  update.noalias() = panel.bottomRows(s.below) * x;
  const int* rows = rows_.data() + s.row_begin;
  for (int i = 0; i < s.below; ++i) {
    const int in_top = top ? top_column_offset_[std::size_t(rows[i])] : -1;
    if (in_top >= 0)
      top[in_top] -= update[i];
    else
      work_[rows[i]] -= update[i];
  }
}

void SupernodalLdlt::backward(int t, Eigen::VectorXd& gathered) {
  const Supernode& s = nodes_[std::size_t(t)];
  const Eigen::Map<const Eigen::MatrixXd> panel(values_.data() + s.value_begin, s.width + s.below,
                                                s.width);
  auto x = work_.segment(s.first, s.width);
  if (s.below > 0) {
    auto known = gathered.head(s.below);
    const int* rows = rows_.data() + s.row_begin;
    for (int i = 0; i < s.below; ++i) known[i] = work_[rows[i]];
    x.noalias() -= panel.bottomRows(s.below).transpose() * known;
  }
  panel.topRows(s.width).triangularView<Eigen::UnitLower>().transpose().solveInPlace(x);
}

void SupernodalLdlt::solve_in_place(Eigen::VectorXd& b, ThreadPool* pool) {
  if (p_.size() > 0)
    work_ = p_ * b;
  else
    work_ = b;
  const int count = int(nodes_.size());
  const bool split = pool && pool->workers() >= 2 && splits();
  // L y = b, panel by panel: the diagonal block's triangle, then its rows below at once. Split,
  // the two groups of subtrees at once (the second's updates to the top's rows through a copy,
  // added afterwards), then the top.
  if (split) {
    top_work_.setZero();
    pool->run([&](int worker) {
      if (worker > 1) return;
      Eigen::VectorXd& gathered = worker == 0 ? gathered_ : gathered_second_;
      for (int t = 0; t < count; ++t)
        if (group_[std::size_t(t)] == worker)
          forward(t, gathered, worker == 1 ? top_work_.data() : nullptr);
    });
    for (int t : top_) {
      const Supernode& n = nodes_[std::size_t(t)];
      work_.segment(n.first, n.width) +=
          top_work_.segment(top_column_offset_[std::size_t(n.first)], n.width);
    }
    for (int t : top_) forward(t, gathered_, nullptr);
  } else {
    for (int t = 0; t < count; ++t) forward(t, gathered_, nullptr);
  }
  work_.array() *= inverse_diagonal_.array();
  // L' x = y, panels in reverse: the top, then the two groups at once (each reads its own
  // columns and its ancestors').
  if (split) {
    for (auto t = top_.rbegin(); t != top_.rend(); ++t) backward(*t, gathered_);
    pool->run([&](int worker) {
      if (worker > 1) return;
      Eigen::VectorXd& gathered = worker == 0 ? gathered_ : gathered_second_;
      for (int t = count - 1; t >= 0; --t)
        if (group_[std::size_t(t)] == worker) backward(t, gathered);
    });
  } else {
    for (int t = count - 1; t >= 0; --t) backward(t, gathered_);
  }
  if (p_inverse_.size() > 0)
    b = p_inverse_ * work_;
  else
    b = work_;
}

}  // namespace handlab::sim
