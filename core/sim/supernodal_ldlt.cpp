#include "core/sim/supernodal_ldlt.h"

#include <algorithm>
#include <stdexcept>

namespace handlab::sim {

void SupernodalLdlt::find_structure(const Eigen::SparseMatrix<double>& l) {
  const int n = int(l.cols());
  const int* outer = l.outerIndexPtr();
  const int* inner = l.innerIndexPtr();
  auto count = [&](int j) { return outer[j + 1] - outer[j]; };
  // Column j + 1 continues j's supernode when j's rows are j + 1 followed by exactly j + 1's.
  auto continues = [&](int j) {
    return count(j) == count(j + 1) + 1 && inner[outer[j]] == j + 1 &&
           std::equal(inner + outer[j] + 1, inner + outer[j + 1], inner + outer[j + 1]);
  };
  nodes_.clear();
  rows_.clear();
  column_to_panel_.assign(std::size_t(n), 0);
  int values = 0;
  for (int j = 0; j < n;) {
    Supernode s;
    s.first = j;
    s.width = 1;
    while (j + s.width < n && continues(j + s.width - 1)) ++s.width;
    const int last = j + s.width - 1;
    s.below = count(last);
    s.row_begin = int(rows_.size());
    rows_.insert(rows_.end(), inner + outer[last], inner + outer[last + 1]);
    s.value_begin = values;
    const int height = s.width + s.below;
    for (int c = 0; c < s.width; ++c)
      column_to_panel_[std::size_t(j + c)] = values + c * height + c + 1;
    values += height * s.width;
    nodes_.push_back(s);
    j += s.width;
  }
  // The diagonal blocks' unit diagonal and zero upper parts stay; set() fills the rest.
  values_.assign(std::size_t(values), 0.0);
  for (const Supernode& s : nodes_)
    for (int c = 0; c < s.width; ++c)
      values_[std::size_t(s.value_begin + c * (s.width + s.below) + c)] = 1.0;
  gathered_.resize(n);
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
  for (int j = 0; j < n; ++j)
    std::copy(lx + outer[j], lx + outer[j + 1], values_.begin() + column_to_panel_[std::size_t(j)]);
  inverse_diagonal_ = factor.vectorD().cwiseInverse();
  p_ = factor.permutationP();
  p_inverse_ = factor.permutationPinv();
}

void SupernodalLdlt::solve_in_place(Eigen::VectorXd& b) const {
  using Panel = Eigen::Map<const Eigen::MatrixXd>;
  if (p_.size() > 0)
    work_ = p_ * b;
  else
    work_ = b;
  // L y = b, panel by panel: the diagonal block's triangle, then its rows below at once.
  for (const Supernode& s : nodes_) {
    const Panel panel(values_.data() + s.value_begin, s.width + s.below, s.width);
    auto x = work_.segment(s.first, s.width);
    panel.topRows(s.width).triangularView<Eigen::UnitLower>().solveInPlace(x);
    if (s.below == 0) continue;
    auto update = gathered_.head(s.below);
    update.noalias() = panel.bottomRows(s.below) * x;
    const int* rows = rows_.data() + s.row_begin;
    for (int i = 0; i < s.below; ++i) work_[rows[i]] -= update[i];
  }
  work_.array() *= inverse_diagonal_.array();
  // L' x = y, panels in reverse.
  for (auto it = nodes_.rbegin(); it != nodes_.rend(); ++it) {
    const Supernode& s = *it;
    const Panel panel(values_.data() + s.value_begin, s.width + s.below, s.width);
    auto x = work_.segment(s.first, s.width);
    if (s.below > 0) {
      auto known = gathered_.head(s.below);
      const int* rows = rows_.data() + s.row_begin;
      for (int i = 0; i < s.below; ++i) known[i] = work_[rows[i]];
      x.noalias() -= panel.bottomRows(s.below).transpose() * known;
    }
    panel.topRows(s.width).triangularView<Eigen::UnitLower>().transpose().solveInPlace(x);
  }
  if (p_inverse_.size() > 0)
    b = p_inverse_ * work_;
  else
    b = work_;
}

}  // namespace handlab::sim
