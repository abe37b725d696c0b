#include "analysis/stats/design_matrices.h"

#include <Eigen/Dense>

#include "analysis/data/long_table.h"

namespace handlab::stats {
namespace {

// k x (k-1) orthonormal basis orthogonal to the constant vector (Helmert, normalised).
Eigen::MatrixXd orthonormal_contrasts(int k) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(k, k - 1);
  for (int j = 1; j < k; ++j) {
    h.col(j - 1).head(j).setConstant(-1.0);
    h(j, j - 1) = j;
    h.col(j - 1).normalize();
  }
  return h;
}

Eigen::MatrixXd kronecker(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd k(a.rows() * b.rows(), a.cols() * b.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
  return k;
}

}  // namespace

std::vector<std::vector<int>> within_effects(int factor_count) {
  std::vector<std::vector<int>> effects = {{}};
  for (int size = 1; size <= factor_count; ++size) {
    // Combinations of `size` factors in lexicographic order.
    std::vector<int> c(static_cast<std::size_t>(size));
    for (int i = 0; i < size; ++i) c[std::size_t(i)] = i;
    while (true) {
      effects.push_back(c);
      int i = size - 1;
      while (i >= 0 && c[std::size_t(i)] == factor_count - size + i) --i;
      if (i < 0) break;
      ++c[std::size_t(i)];
      for (int j = i + 1; j < size; ++j) c[std::size_t(j)] = c[std::size_t(j - 1)] + 1;
    }
  }
  return effects;
}

Eigen::MatrixXd within_contrast(const RmData& data, const std::vector<int>& effect) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Ones(1, 1);
  // The first factor varies fastest in the cell index, so it is the innermost Kronecker factor.
  for (int f = 0; f < int(data.within.size()); ++f) {
    const int k = int(data.within[std::size_t(f)].levels.size());
    const bool in_effect = std::find(effect.begin(), effect.end(), f) != effect.end();
    const Eigen::MatrixXd basis = in_effect
                                      ? orthonormal_contrasts(k)
                                      : Eigen::MatrixXd::Constant(k, 1, 1.0 / std::sqrt(double(k)));
    p = kronecker(basis, p);
  }
  return p;
}

BetweenModel between_model(const RmData& data) {
  const Eigen::Index n = data.y.rows();
  BetweenModel m;
  std::vector<Eigen::VectorXd> columns = {Eigen::VectorXd::Ones(n)};
  m.term_names = {"(Intercept)"};
  m.term_columns = {{0}};
  m.term_variables = {{}};

  // contr.sum columns per between factor.
  std::vector<std::vector<Eigen::VectorXd>> coded(data.between.size());
  for (std::size_t b = 0; b < data.between.size(); ++b) {
    const int k = int(data.between[b].levels.size());
    for (int j = 0; j < k - 1; ++j) {
      Eigen::VectorXd col(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const int level = data.between_levels[std::size_t(i)][b];
        col(i) = level == j ? 1.0 : level == k - 1 ? -1.0 : 0.0;
      }
      coded[b].push_back(col);
    }
  }
  // Every non-empty subset of between factors, in R's term order; columns are products
  // with the first factor's column varying fastest.
  for (const auto& term : within_effects(int(data.between.size()))) {
    if (term.empty()) continue;
    std::vector<Eigen::VectorXd> products = {Eigen::VectorXd::Ones(n)};
    std::string name;
    std::vector<std::string> variables;
    for (int b : term) {
      std::vector<Eigen::VectorXd> next;
      for (const auto& coded_column : coded[std::size_t(b)])
        for (const auto& p : products) next.push_back(p.cwiseProduct(coded_column));
      // Reorder so the earlier factor varies fastest.
      std::vector<Eigen::VectorXd> ordered;
      const std::size_t inner = products.size(), outer = coded[std::size_t(b)].size();
      for (std::size_t o = 0; o < outer; ++o)
        for (std::size_t i = 0; i < inner; ++i) ordered.push_back(next[o * inner + i]);
      products = std::move(ordered);
      name += (name.empty() ? "" : ":") + data.between[std::size_t(b)].name;
      variables.push_back(data.between[std::size_t(b)].name);
    }
    std::vector<int> cols;
    for (auto& p : products) {
      cols.push_back(int(columns.size()));
      columns.push_back(std::move(p));
    }
    m.term_names.push_back(name);
    m.term_columns.push_back(cols);
    m.term_variables.push_back(variables);
  }
  for (std::size_t k = 0; k < data.covariates.size(); ++k) {
    m.term_names.push_back(data.covariates[k]);
    m.term_columns.push_back({int(columns.size())});
    m.term_variables.push_back({data.covariates[k]});
    columns.push_back(data.covariate_values.col(Eigen::Index(k)));
  }

  m.x.resize(n, Eigen::Index(columns.size()));
  for (std::size_t j = 0; j < columns.size(); ++j) m.x.col(Eigen::Index(j)) = columns[j];
  m.error_df = int(n) - int(columns.size());
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m.x);
  if (qr.rank() < m.x.cols() || m.error_df < 1)
    throw analysis::DataError(
        "the between-participants design is singular or has no error degrees of freedom (" +
        std::to_string(n) + " participants, " + std::to_string(m.x.cols()) + " parameters)");
  m.xtx_inverse = (m.x.transpose() * m.x).inverse();
  return m;
}

}  // namespace handlab::stats
