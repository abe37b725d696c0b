#include "analysis/power/power_analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <Eigen/Cholesky>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/distributions/non_central_t.hpp>

#include "analysis/stats/design_matrices.h"
#include "analysis/stats/nonparametric.h"
#include "analysis/stats/p_adjust.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/ptukey.h"
#include "analysis/stats/rm_anova.h"
#include "analysis/stats/wilson_interval.h"

namespace handlab::power {

JudgedP judged(const stats::AnovaEffect& e, SphericityCorrection correction, double alpha) {
  const JudgedP uncorrected{e.p, 1.0}, gg{e.p_gg, e.eps_gg}, hf{e.p_hf, std::min(1.0, e.eps_hf)};
  if (e.df_num <= 1 || !std::isfinite(e.mauchly_p)) return uncorrected;
  switch (correction) {
    case SphericityCorrection::kNone:
      return uncorrected;
    case SphericityCorrection::kGreenhouseGeisser:
      return gg;
    case SphericityCorrection::kHuynhFeldt:
      return hf;
    case SphericityCorrection::kAuto:
      return e.mauchly_p < alpha ? gg : uncorrected;
  }
  return uncorrected;
}

std::string contrast_name(const stats::PairwiseContrast& c) {
  std::string name = c.effect + ": " + c.contrast;
  if (!c.by.empty()) {
    name += " |";
    for (const auto& [factor, level] : c.by) name += " " + factor + " " + level;
  }
  return name;
}

namespace {

// The covariance of a participant's cells with the covariates' spread included.
Eigen::MatrixXd total_covariance(const PowerModel& m) {
  Eigen::MatrixXd s = m.covariance();
  for (const PowerCovariate& c : m.covariates) s += c.sd * c.sd * c.slope * c.slope.transpose();
  return s;
}

stats::RmData rm_data(const PowerDesign& design, const Eigen::MatrixXd& y) {
  stats::RmData d;
  d.within = design.within();
  d.y = y;
  for (Eigen::Index i = 0; i < y.rows(); ++i) d.subjects.push_back("P" + std::to_string(i + 1));
  d.between_levels.assign(std::size_t(y.rows()), {});
  d.covariate_values.resize(y.rows(), 0);
  return d;
}

std::string spaced(const PowerDesign& d, int condition) {
  std::string label = d.condition_label(condition);
  std::replace(label.begin(), label.end(), '-', ' ');
  return label;
}

// The design's conditions (first factor fastest) in the order analyze numbers them (first
// factor slowest).
std::vector<int> report_order(const PowerDesign& d) {
  std::vector<int> order;
  for (int slow = 0; slow < d.conditions(); ++slow) {
    int index = slow, fast = 0, stride = 1;
    std::vector<int> levels(d.factors.size());
    for (std::size_t k = d.factors.size(); k-- > 0;) {
      const int n = int(d.factors[k].levels.size());
      levels[k] = index % n;
      index /= n;
    }
    for (std::size_t k = 0; k < d.factors.size(); ++k) {
      fast += levels[k] * stride;
      stride *= int(d.factors[k].levels.size());
    }
    order.push_back(fast);
  }
  return order;
}

// What one simulated study rejects, in the order of the names.
struct Outcome {
  std::vector<char> effects, contrasts;
  bool warned = false;
  std::string warning;
};

struct Names {
  std::vector<std::string> effects, contrasts;
};

class Analyser {
 public:
  Analyser(const PowerModel& model, const PowerOptions& options)
      : model_(model), options_(options) {}

  // The analysis `analyze --db` runs, on one simulated study. With `names` empty, fills them.
  Outcome analyse(const SimulatedData& data, Names& names) const {
    const bool naming = names.effects.empty() && names.contrasts.empty();
    Outcome out;
    auto warn = [&](const std::string& w) {
      if (!out.warned) out.warning = w;
      out.warned = true;
    };
    // Participants with every cell (as the ANOVA of a study database keeps them).
    std::vector<Eigen::Index> complete;
    for (Eigen::Index i = 0; i < data.cells.rows(); ++i)
      if (!data.cells.row(i).array().isNaN().any()) complete.push_back(i);
    if (Eigen::Index(complete.size()) < data.cells.rows())
      warn(std::to_string(data.cells.rows() - Eigen::Index(complete.size())) +
           " participant(s) left out, lacking a result in some cell");
    const std::vector<std::vector<int>> within =
        stats::within_effects(int(model_.design.within().size()));
    if (naming) {
      const stats::RmData probe =
          rm_data(model_.design, Eigen::MatrixXd::Zero(1, model_.design.cells()));
      for (std::size_t k = 1; k < within.size(); ++k)
        names.effects.push_back(probe.effect_label(within[k]));
    }
    // The ANOVA's effects first; the items' tests are appended after them.
    const std::size_t anova_effects = within.size() - 1;
    out.effects.assign(anova_effects, 0);
    std::vector<std::string> contrast_seen;
    if (complete.size() >= 3) {
      Eigen::MatrixXd y(Eigen::Index(complete.size()), data.cells.cols());
      for (std::size_t i = 0; i < complete.size(); ++i)
        y.row(Eigen::Index(i)) = data.cells.row(complete[i]);
      const stats::RmData rm = rm_data(model_.design, y);
      try {
        const stats::AnovaResult anova = stats::rm_anova(rm);
        for (const stats::AnovaEffect& e : anova.effects) {
          const auto last = names.effects.begin() + std::ptrdiff_t(anova_effects);
          const auto at = std::find(names.effects.begin(), last, e.effect);
          if (at == last) continue;
          const double p = judged_p(e, options_.correction, options_.alpha);
          if (!std::isfinite(p)) warn("effect " + e.effect + ": no p value");
          out.effects[std::size_t(at - names.effects.begin())] = p < options_.alpha;
        }
        for (const std::string& effect : model_.contrast_effects) {
          stats::PosthocSpec spec = stats::PosthocSpec::parse(effect, rm);
          spec.r_level_names = false;
          const stats::PosthocResult r = stats::pairwise_comparisons(rm, spec);
          for (const stats::PairwiseContrast& c : r.contrasts) {
            contrast_seen.push_back(contrast_name(c));
            out.contrasts.push_back(c.p_tukey < options_.alpha);
          }
        }
      } catch (const std::exception& e) {
        warn(std::string("analysis failed: ") + e.what());
      }
    } else {
      warn("fewer than three participants with every cell");
    }
    // Questionnaire items: Friedman over the conditions, Wilcoxon for every pair (Bonferroni).
    const int q = model_.design.conditions();
    for (std::size_t k = 0; k < model_.items.size(); ++k) {
      const std::string& item = model_.items[k].name;
      if (naming) names.effects.push_back(item + " (Friedman)");
      const Eigen::MatrixXd& a = data.items[k];
      const stats::FriedmanResult f = stats::friedman_test(a);
      if (!std::isfinite(f.p)) warn(item + ": Friedman test without a p value (every answer tied)");
      out.effects.push_back(std::isfinite(f.p) && f.p < options_.alpha);
      std::vector<double> p;
      // Pairs in the order analyze takes them (the first factor varying slowest).
      const std::vector<int> order = report_order(model_.design);
      for (int ii = 0; ii < q; ++ii)
        for (int jj = ii + 1; jj < q; ++jj) {
          const int i = order[std::size_t(ii)], j = order[std::size_t(jj)];
          std::vector<double> x(a.col(i).data(), a.col(i).data() + a.rows());
          std::vector<double> z(a.col(j).data(), a.col(j).data() + a.rows());
          const double pij = stats::wilcoxon_signed_rank(x, z).p;
          p.push_back(std::isfinite(pij) ? pij : 1.0);
          contrast_seen.push_back(item + ": " + spaced(model_.design, i) + " - " +
                                  spaced(model_.design, j) + " (Wilcoxon)");
        }
      for (double b : stats::p_adjust_bonferroni(p)) out.contrasts.push_back(b < options_.alpha);
    }
    if (naming) names.contrasts = contrast_seen;
    if (contrast_seen != names.contrasts) {
      // A failed analysis has no contrasts: none rejected.
      out.contrasts.assign(names.contrasts.size(), 0);
      if (!contrast_seen.empty()) warn("post hoc contrasts differ from the first simulation's");
    }
    return out;
  }

 private:
  const PowerModel& model_;
  const PowerOptions& options_;
};

PowerEstimate estimate(const std::string& name, std::size_t n_count) {
  PowerEstimate e;
  e.name = name;
  e.power.assign(n_count, 0.0);
  e.mc_se.assign(n_count, 0.0);
  e.lower.assign(n_count, 0.0);
  e.upper.assign(n_count, 0.0);
  return e;
}

void set_binomial(PowerEstimate& e, std::size_t k, long hits, int sims) {
  const double n = sims, p = double(hits) / n;
  e.power[k] = p;
  e.mc_se[k] = std::sqrt(p * (1 - p) / n);
  const stats::ProportionInterval interval = stats::wilson_interval(double(hits), n);
  e.lower[k] = interval.low;
  e.upper[k] = interval.high;
}

void check_options(const PowerOptions& o) {
  if (o.n.empty()) throw std::invalid_argument("no N to compute the power for");
  for (int n : o.n)
    if (n < 3) throw std::invalid_argument("every N must be 3 or more");
  if (!(o.alpha > 0 && o.alpha < 1)) throw std::invalid_argument("alpha must be in (0, 1)");
}

// q with P(Q > q) = alpha for the studentized range of `means` means.
double tukey_critical(double means, double df, double alpha) {
  const stats::TukeyFamily family(means, df);
  double low = 0.0, high = 1.0;
  while (family.upper(high) > alpha) high *= 2;
  for (int i = 0; i < 100 && high - low > 1e-10 * high; ++i) {
    const double mid = 0.5 * (low + high);
    (family.upper(mid) > alpha ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace

std::optional<int> n_for_target(const PowerReport& report, const PowerEstimate& e, double target) {
  for (std::size_t k = 0; k < report.n.size(); ++k)
    if (e.power[k] >= target) return report.n[k];
  return std::nullopt;
}

PowerReport empty_report(const std::vector<std::string>& effects,
                         const std::vector<std::string>& contrasts, const std::vector<int>& n,
                         int sims, double alpha) {
  PowerReport report;
  report.n = n;
  report.sims = sims;
  report.alpha = alpha;
  for (const std::string& e : effects) report.effects.push_back(estimate(e, n.size()));
  for (const std::string& c : contrasts) report.contrasts.push_back(estimate(c, n.size()));
  report.warnings.assign(n.size(), 0);
  report.seconds.assign(n.size(), 0.0);
  return report;
}

void set_counts(PowerReport& report, std::size_t k, const std::vector<long>& effect_hits,
                const std::vector<long>& contrast_hits, int warnings, double seconds) {
  for (std::size_t e = 0; e < report.effects.size(); ++e)
    set_binomial(report.effects[e], k, effect_hits.at(e), report.sims);
  for (std::size_t c = 0; c < report.contrasts.size(); ++c)
    set_binomial(report.contrasts[c], k, contrast_hits.at(c), report.sims);
  report.warnings.at(k) = warnings;
  report.seconds.at(k) = seconds;
}

SimulatedData simulate_data(const PowerModel& model, int n, util::PortableRandom& random) {
  const int cells = model.design.cells(), q = model.design.conditions();
  const Eigen::MatrixXd l = model.covariance().llt().matrixL();
  SimulatedData d;
  d.cells.resize(n, cells);
  d.covariates.resize(n, Eigen::Index(model.covariates.size()));
  std::vector<Eigen::MatrixXd> item_l;
  for (const PowerItem& item : model.items) {
    item_l.push_back(
        Eigen::MatrixXd(exchangeable_correlation(q, item.correlation).llt().matrixL()));
    d.items.emplace_back(n, q);
  }
  Eigen::VectorXd z(cells), zq(q);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < cells; ++c) z[c] = random.normal();
    Eigen::VectorXd y = model.mean + l * z;
    for (std::size_t k = 0; k < model.covariates.size(); ++k) {
      const PowerCovariate& cov = model.covariates[k];
      const double x = cov.mean + cov.sd * random.normal();
      d.covariates(i, Eigen::Index(k)) = x;
      y += (x - cov.mean) * cov.slope;
    }
    for (int c = 0; c < cells; ++c)
      if (model.missing > 0 && random.uniform() < model.missing) y[c] = std::nan("");
    d.cells.row(i) = y.transpose();
    for (std::size_t k = 0; k < model.items.size(); ++k) {
      const PowerItem& item = model.items[k];
      for (int c = 0; c < q; ++c) zq[c] = random.normal();
      const Eigen::VectorXd latent = item.mean + item.sd * (item_l[k] * zq);
      for (int c = 0; c < q; ++c)
        d.items[k](i, c) = std::clamp(std::round(latent[c]), 1.0, double(item.scale_points));
    }
  }
  return d;
}

PowerReport simulate_power(const PowerModel& model, const PowerOptions& options,
                           const std::function<void(int, int)>& progress) {
  check_options(options);
  if (options.sims < 1) throw std::invalid_argument("sims must be 1 or more");
  const Analyser analyser(model, options);
  // The names come from one analysis of a study without missing results.
  Names names;
  {
    PowerModel whole = model;
    whole.missing = 0;
    util::PortableRandom random(util::splitmix64(options.seed));
    analyser.analyse(simulate_data(whole, std::max(options.n.front(), 3), random), names);
  }
  PowerReport report =
      empty_report(names.effects, names.contrasts, options.n, options.sims, options.alpha);
  report.notes = model.notes;
  const int threads = std::max(1, options.threads);
  for (std::size_t k = 0; k < options.n.size(); ++k) {
    const int n = options.n[k];
    const auto start = std::chrono::steady_clock::now();
    struct Tally {
      std::vector<long> effects, contrasts;
      int warnings = 0;
      std::string example;
    };
    std::vector<Tally> tallies{std::size_t(threads)};
    auto work = [&](int t) {
      Tally& tally = tallies[std::size_t(t)];
      tally.effects.assign(names.effects.size(), 0);
      tally.contrasts.assign(names.contrasts.size(), 0);
      Names fixed = names;
      // Simulation s draws from its own stream: the same data whatever thread runs it.
      for (int s = t; s < options.sims; s += threads) {
        util::PortableRandom random(util::splitmix64(
            options.seed ^
            util::splitmix64(std::uint64_t(n) * 0x100000001B3ull + std::uint64_t(s))));
        const Outcome o = analyser.analyse(simulate_data(model, n, random), fixed);
        for (std::size_t e = 0; e < tally.effects.size(); ++e) tally.effects[e] += o.effects.at(e);
        for (std::size_t c = 0; c < tally.contrasts.size(); ++c)
          tally.contrasts[c] += o.contrasts.at(c);
        if (o.warned) {
          if (tally.warnings++ == 0) tally.example = o.warning;
        }
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& th : pool) th.join();
    std::vector<long> effect_hits(names.effects.size(), 0),
        contrast_hits(names.contrasts.size(), 0);
    int warnings = 0;
    for (const Tally& t : tallies) {
      for (std::size_t e = 0; e < effect_hits.size(); ++e) effect_hits[e] += t.effects[e];
      for (std::size_t c = 0; c < contrast_hits.size(); ++c) contrast_hits[c] += t.contrasts[c];
      warnings += t.warnings;
      if (t.warnings && report.warning_examples.size() < 5)
        report.warning_examples.push_back("N = " + std::to_string(n) + ": " + t.example);
    }
    set_counts(report, k, effect_hits, contrast_hits, warnings,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (progress) progress(int(k + 1), int(options.n.size()));
  }
  return report;
}

PowerReport exact_power(const PowerModel& model, const PowerOptions& options) {
  check_options(options);
  namespace bm = boost::math;
  PowerReport report;
  report.n = options.n;
  report.alpha = options.alpha;
  report.notes = model.notes;
  const PowerDesign& design = model.design;
  const stats::RmData shape = rm_data(design, Eigen::MatrixXd::Zero(1, design.cells()));
  const Eigen::MatrixXd sigma = total_covariance(model);
  const auto within = stats::within_effects(int(shape.within.size()));
  // Participants expected to have every cell.
  const double complete = std::pow(1.0 - model.missing, design.cells());
  if (model.missing > 0)
    report.notes.push_back("exact: N is the expected number of participants with every cell, N x " +
                           std::to_string(complete));
  if (!model.items.empty())
    report.notes.push_back("exact: the questionnaire items have no exact answer here; simulate");
  for (std::size_t w = 1; w < within.size(); ++w) {
    PowerEstimate e = estimate(shape.effect_label(within[w]), options.n.size());
    const Eigen::MatrixXd c = stats::within_contrast(shape, within[w]).transpose();  // d x cells
    const double df1 = double(c.rows());
    const double signal = (c * model.mean).squaredNorm();
    const double noise = (c * sigma * c.transpose()).trace();
    for (std::size_t k = 0; k < options.n.size(); ++k) {
      const double n = options.n[k] * complete;
      const double df2 = df1 * (n - 1);
      const double lambda = df1 * n * signal / noise;
      const double critical = bm::quantile(bm::complement(bm::fisher_f(df1, df2), options.alpha));
      e.power[k] = lambda > 0
                       ? bm::cdf(bm::complement(bm::non_central_f(df1, df2, lambda), critical))
                       : options.alpha;
      e.lower[k] = e.upper[k] = e.power[k];
    }
    report.effects.push_back(e);
  }
  // Tukey contrasts: |t| beyond the studentized range's critical value / sqrt(2).
  for (const std::string& effect : model.contrast_effects) {
    Eigen::MatrixXd probe = Eigen::MatrixXd::Zero(3, design.cells());
    probe(0, 0) = 1;
    const stats::RmData rm = rm_data(design, probe);
    stats::PosthocSpec spec = stats::PosthocSpec::parse(effect, rm);
    spec.r_level_names = false;
    const stats::PosthocResult r = stats::pairwise_comparisons(rm, spec);
    for (const stats::PairwiseContrast& pc : r.contrasts) {
      PowerEstimate e = estimate(contrast_name(pc), options.n.size());
      // Cell weights: +1/m over the first combination's cells, -1/m over the second's.
      Eigen::VectorXd w = Eigen::VectorXd::Zero(design.cells());
      auto matches = [&](int cell, const std::vector<std::pair<std::string, std::string>>& at) {
        const std::vector<int> levels = rm.cell_levels(cell);
        for (const auto& [factor, level] : at)
          for (std::size_t f = 0; f < rm.within.size(); ++f)
            if (rm.within[f].name == factor && rm.within[f].levels[std::size_t(levels[f])] != level)
              return false;
        return true;
      };
      auto with_by = [&](std::vector<std::pair<std::string, std::string>> at) {
        at.insert(at.end(), pc.by.begin(), pc.by.end());
        return at;
      };
      const auto first = with_by(pc.first), second = with_by(pc.second);
      int in_first = 0, in_second = 0;
      for (int cell = 0; cell < design.cells(); ++cell) {
        in_first += matches(cell, first);
        in_second += matches(cell, second);
      }
      for (int cell = 0; cell < design.cells(); ++cell) {
        if (matches(cell, first)) w[cell] += 1.0 / in_first;
        if (matches(cell, second)) w[cell] -= 1.0 / in_second;
      }
      int family = 1;  // the means compared in one by-group
      for (const std::string& f : spec.factors)
        for (const stats::Factor& factor : rm.within)
          if (factor.name == f) family *= int(factor.levels.size());
      const double delta = w.dot(model.mean), sd = std::sqrt(w.dot(sigma * w));
      for (std::size_t k = 0; k < options.n.size(); ++k) {
        const double n = options.n[k] * complete, df = n - 1;
        const double critical =
            family > 2 ? tukey_critical(family, df, options.alpha) / std::sqrt(2.0)
                       : bm::quantile(bm::complement(bm::students_t(df), options.alpha / 2));
        const double ncp = delta / sd * std::sqrt(n);
        const bm::non_central_t t(df, ncp);
        e.power[k] = bm::cdf(bm::complement(t, critical)) + bm::cdf(t, -critical);
        e.lower[k] = e.upper[k] = e.power[k];
      }
      report.contrasts.push_back(e);
    }
  }
  report.warnings.assign(options.n.size(), 0);
  report.seconds.assign(options.n.size(), 0.0);
  return report;
}

}  // namespace handlab::power
