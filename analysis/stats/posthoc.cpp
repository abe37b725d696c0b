#include "analysis/stats/posthoc.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>

#include <Eigen/Dense>

#include "analysis/data/long_table.h"
#include "analysis/stats/design_matrices.h"
#include "analysis/stats/distributions.h"
#include "analysis/stats/p_adjust.h"
#include "analysis/stats/ptukey.h"

namespace handlab::stats {
namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, sep))
    if (!part.empty()) parts.push_back(part);
  return parts;
}

int within_index(const RmData& data, const std::string& name) {
  for (std::size_t f = 0; f < data.within.size(); ++f)
    if (data.within[f].name == name) return int(f);
  throw analysis::DataError("post hoc: '" + name + "' is not a within factor of the design");
}

}  // namespace

std::string emmeans_level_label(const std::string& level) {
  if (level.empty()) return level;
  const unsigned char c = static_cast<unsigned char>(level[0]);
  const bool valid_start =
      std::isalpha(c) ||
      (c == '.' && !(level.size() > 1 && std::isdigit(static_cast<unsigned char>(level[1]))));
  return valid_start ? level : "X" + level;
}

PosthocSpec PosthocSpec::parse(const std::string& text, const RmData& data) {
  PosthocSpec spec;
  const auto bar = text.find('|');
  spec.factors = split(text.substr(0, bar), ':');
  if (bar != std::string::npos) spec.by = split(text.substr(bar + 1), ':');
  if (spec.factors.empty())
    throw analysis::DataError("post hoc: no factor named in '" + text + "'");
  for (const auto& f : spec.factors) within_index(data, f);
  for (const auto& f : spec.by) {
    within_index(data, f);
    if (std::find(spec.factors.begin(), spec.factors.end(), f) != spec.factors.end())
      throw analysis::DataError("post hoc: '" + f + "' is both compared and a by factor");
  }
  return spec;
}

std::string PosthocSpec::effect() const {
  std::string e;
  for (const auto& f : factors) e += (e.empty() ? "" : ":") + f;
  return e;
}

PosthocResult pairwise_comparisons(const RmData& data, const PosthocSpec& spec) {
  const BetweenModel model = between_model(data);
  const double df = model.error_df;
  const double intercept_var = model.xtx_inverse(0, 0);
  // The intercept of the participant-level regression of scores on X: with sum-to-zero
  // between contrasts and centred covariates it is the equally weighted marginal mean.

  std::vector<int> spec_f, by_f;
  for (const auto& f : spec.factors) spec_f.push_back(within_index(data, f));
  for (const auto& f : spec.by) by_f.push_back(within_index(data, f));
  auto count_cells = [&](const std::vector<int>& factors) {
    int n = 1;
    for (int f : factors) n *= int(data.within[std::size_t(f)].levels.size());
    return n;
  };
  const int spec_cells = count_cells(spec_f), by_cells = count_cells(by_f);

  // Averaging weights: column (s + spec_cells * g) averages the within cells whose spec
  // factors give combination s and by factors give combination g.
  Eigen::MatrixXd averaging = Eigen::MatrixXd::Zero(data.cells(), spec_cells * by_cells);
  auto combination = [&](const std::vector<int>& levels, const std::vector<int>& factors) {
    int index = 0, stride = 1;
    for (int f : factors) {
      index += stride * levels[std::size_t(f)];
      stride *= int(data.within[std::size_t(f)].levels.size());
    }
    return index;
  };
  for (int c = 0; c < data.cells(); ++c) {
    const auto levels = data.cell_levels(c);
    averaging(c, combination(levels, spec_f) + spec_cells * combination(levels, by_f)) = 1.0;
  }
  for (Eigen::Index j = 0; j < averaging.cols(); ++j) averaging.col(j) /= averaging.col(j).sum();

  auto level_of = [&](int combo, const std::vector<int>& factors, std::size_t which) {
    for (std::size_t i = 0; i < which; ++i)
      combo /= int(data.within[std::size_t(factors[i])].levels.size());
    return combo % int(data.within[std::size_t(factors[which])].levels.size());
  };
  auto label = [&](int combo, const std::vector<int>& factors) {
    std::string text;
    for (std::size_t i = 0; i < factors.size(); ++i) {
      const std::string& level =
          data.within[std::size_t(factors[i])].levels[std::size_t(level_of(combo, factors, i))];
      text += (i ? " " : "") + (spec.r_level_names ? emmeans_level_label(level) : level);
    }
    return text;
  };
  auto at = [&](int combo, const std::vector<int>& factors) {
    std::vector<std::pair<std::string, std::string>> pairs;
    for (std::size_t i = 0; i < factors.size(); ++i)
      pairs.emplace_back(
          data.within[std::size_t(factors[i])].name,
          data.within[std::size_t(factors[i])].levels[std::size_t(level_of(combo, factors, i))]);
    return pairs;
  };
  // Participants' marginal means of every compared cell, once; each estimate and contrast
  // below is a combination of its columns.
  const Eigen::MatrixXd marginal = data.y * averaging;
  const Eigen::MatrixXd projector = model.xtx_inverse * model.x.transpose();
  auto test = [&](const Eigen::VectorXd& scores, double* estimate, double* se) {
    const Eigen::VectorXd beta = projector * scores;
    *estimate = beta(0);
    *se = std::sqrt((scores - model.x * beta).squaredNorm() / df * intercept_var);
  };

  PosthocResult result;
  const double t_crit = t_upper_quantile(0.025, df);
  for (int g = 0; g < by_cells; ++g) {
    for (int s = 0; s < spec_cells; ++s) {
      MarginalMean m;
      m.at = at(s, spec_f);
      for (auto& p : at(g, by_f)) m.at.push_back(p);
      test(marginal.col(s + spec_cells * g), &m.estimate, &m.se);
      m.df = df;
      m.lower_cl = m.estimate - t_crit * m.se;
      m.upper_cl = m.estimate + t_crit * m.se;
      result.means.push_back(m);
    }
  }
  // Tukey's test of spec_cells means: every by-group has the same means and df, so one
  // family serves them all.
  std::optional<TukeyFamily> family;
  if (spec_cells > 2) family.emplace(spec_cells, df);
  auto tukey = [&](double q) { return family->upper(q); };
  for (int g = 0; g < by_cells; ++g) {
    std::vector<double> group_p;
    const std::size_t first = result.contrasts.size();
    for (int a = 0; a < spec_cells; ++a) {
      for (int b = a + 1; b < spec_cells; ++b) {
        PairwiseContrast c;
        c.effect = spec.effect();
        c.contrast = label(a, spec_f) + " - " + label(b, spec_f);
        c.by = at(g, by_f);
        c.first = at(a, spec_f);
        c.second = at(b, spec_f);
        test(marginal.col(a + spec_cells * g) - marginal.col(b + spec_cells * g), &c.estimate,
             &c.se);
        c.df = df;
        c.t = c.estimate / c.se;
        c.p_none = t_two_sided(c.t, df);
        // Tukey's HSD over the spec_cells means of this group: the studentized range of
        // |t|·sqrt(2); with two means it equals the unadjusted p.
        c.p_tukey = spec_cells > 2 ? tukey(std::abs(c.t) * std::sqrt(2.0)) : c.p_none;
        group_p.push_back(c.p_none);
        result.contrasts.push_back(c);
      }
    }
    const auto bonferroni = p_adjust_bonferroni(group_p);
    const auto holm = p_adjust_holm(group_p);
    for (std::size_t i = 0; i < group_p.size(); ++i) {
      result.contrasts[first + i].p_bonferroni = bonferroni[i];
      result.contrasts[first + i].p_holm = holm[i];
    }
  }
  std::vector<double> all_p;
  for (const auto& c : result.contrasts) all_p.push_back(c.p_none);
  const auto bonferroni_all = p_adjust_bonferroni(all_p);
  const auto holm_all = p_adjust_holm(all_p);
  for (std::size_t i = 0; i < all_p.size(); ++i) {
    result.contrasts[i].p_bonferroni_all = bonferroni_all[i];
    result.contrasts[i].p_holm_all = holm_all[i];
  }
  return result;
}

}  // namespace handlab::stats
