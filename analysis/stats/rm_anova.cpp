#include "analysis/stats/rm_anova.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "analysis/stats/design_matrices.h"
#include "analysis/stats/distributions.h"

namespace handlab::stats {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Sphericity {
  double w = kNaN, p = kNaN, gg = kNaN, hf = kNaN;
};

// Mauchly's test and the epsilons from the error SSP matrix of an effect in an orthonormal
// basis. As car does, the second-order term of Mauchly's p uses the total number of within
// cells (`cells`) where the effect's dimension might be expected.
Sphericity sphericity(const Eigen::MatrixXd& sspe, int error_df, int cells) {
  Sphericity s;
  const int d = int(sspe.rows());
  if (d < 2) return s;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(sspe, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  double sum = 0.0, sum_sq = 0.0, log_det = 0.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) > 0) {
      sum += lambda(i);
      sum_sq += lambda(i) * lambda(i);
    }
    log_det += std::log(lambda(i));  // -inf or NaN when singular: W is then 0 / undefined
  }
  s.gg = (sum / d) * (sum / d) / (sum_sq / d);
  s.hf = ((error_df + 1.0) * d * s.gg - 2.0) / (d * (error_df - d * s.gg));

  const double n = error_df;
  const double log_w = log_det - d * std::log(sum / d);
  const double rho = 1.0 - (2.0 * d * d + d + 2.0) / (6.0 * d * n);
  const double w2 = (d + 2.0) * (d - 1.0) * (d - 2.0) *
                    (2.0 * d * d * d + 6.0 * d * d + 3.0 * cells + 2.0) /
                    (288.0 * (n * d * rho) * (n * d * rho));
  const double z = -n * rho * log_w;
  const double f = d * (d + 1.0) / 2.0 - 1.0;
  const double pr1 = chi_squared_upper_tail(z, f);
  const double pr2 = chi_squared_upper_tail(z, f + 4.0);
  s.w = std::exp(log_w);
  s.p = pr1 + w2 * (pr2 - pr1);
  return s;
}

bool mentions_observed(const std::vector<std::string>& variables,
                       const std::vector<std::string>& observed) {
  int count = 0;
  for (const auto& v : variables) count += int(std::count(observed.begin(), observed.end(), v));
  return count > 0;
}

}  // namespace

AnovaResult rm_anova(const RmData& data) {
  const BetweenModel model = between_model(data);
  const Eigen::MatrixXd projector = model.xtx_inverse * model.x.transpose();  // q x N
  AnovaResult result;
  result.n_subjects = int(data.y.rows());

  struct Row {
    AnovaEffect effect;
    std::vector<std::string> observed_variables;
  };
  std::vector<Row> rows;
  std::vector<double> error_ss;  // one per within stratum
  for (const auto& within : within_effects(int(data.within.size()))) {
    const Eigen::MatrixXd p = within_contrast(data, within);
    const Eigen::MatrixXd z = data.y * p;     // N x d transformed responses
    const Eigen::MatrixXd b = projector * z;  // q x d coefficients
    const Eigen::MatrixXd residual = z - model.x * b;
    const Eigen::MatrixXd sspe = residual.transpose() * residual;
    const int d = int(p.cols());
    const double sse = sspe.trace();
    error_ss.push_back(sse);
    const Sphericity sph = sphericity(sspe, model.error_df, data.cells());

    for (std::size_t t = 0; t < model.term_names.size(); ++t) {
      const auto& cols = model.term_columns[t];
      const Eigen::Index k = Eigen::Index(cols.size());
      Eigen::MatrixXd bt(k, d), m(k, k);
      for (Eigen::Index i = 0; i < k; ++i) {
        bt.row(i) = b.row(cols[std::size_t(i)]);
        for (Eigen::Index j = 0; j < k; ++j)
          m(i, j) = model.xtx_inverse(cols[std::size_t(i)], cols[std::size_t(j)]);
      }
      // Type 3: SSP_H = (L B)' (L (X'X)^-1 L')^-1 (L B); with orthonormal contrasts SS = trace.
      const double ss = (bt.transpose() * m.ldlt().solve(bt)).trace();

      Row row;
      AnovaEffect& e = row.effect;
      std::string name = t == 0 ? std::string() : model.term_names[t];
      const std::string within_name = data.effect_label(within);
      if (!within_name.empty()) name += (name.empty() ? "" : ":") + within_name;
      e.effect = name.empty() ? "(Intercept)" : name;
      e.df_num = double(k * d);
      e.df_den = double(model.error_df * d);
      e.ss = ss;
      e.ss_error = sse;
      e.mse = sse / e.df_den;
      e.f = (ss / e.df_num) / e.mse;
      e.p = f_upper_tail(e.f, e.df_num, e.df_den);
      e.pes = ss / (ss + sse);
      e.mauchly_w = sph.w;
      e.mauchly_p = sph.p;
      e.eps_gg = sph.gg;
      e.eps_hf = sph.hf;
      e.p_gg = std::isnan(sph.gg) ? kNaN : f_upper_tail(e.f, e.df_num * sph.gg, e.df_den * sph.gg);
      const double hf = std::min(1.0, sph.hf);
      e.p_hf = std::isnan(sph.hf) ? kNaN : f_upper_tail(e.f, e.df_num * hf, e.df_den * hf);
      row.observed_variables = model.term_variables[t];
      rows.push_back(std::move(row));
    }
  }

  // Generalised eta squared (Olejnik & Algina 2003, as afex): the effect's SS over itself
  // plus every distinct error SS plus the SS of effects involving observed variables.
  std::sort(error_ss.begin(), error_ss.end());
  error_ss.erase(std::unique(error_ss.begin(), error_ss.end()), error_ss.end());
  double total_error = 0.0;
  for (double s : error_ss) total_error += s;
  double observed_ss = 0.0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].effect.effect != "(Intercept)" &&
        mentions_observed(rows[i].observed_variables, data.observed))
      observed_ss += rows[i].effect.ss;
  for (auto& row : rows) {
    AnovaEffect& e = row.effect;
    const double own = mentions_observed(row.observed_variables, data.observed) ? e.ss : 0.0;
    e.ges = e.ss / (e.ss + total_error + observed_ss - own);
    if (e.effect == "(Intercept)")
      result.intercept = e;
    else
      result.effects.push_back(e);
  }
  return result;
}

}  // namespace handlab::stats
