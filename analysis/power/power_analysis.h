// Simulation-based power of a repeated-measures design (docs/power.md): for every number of
// participants, data sets drawn from a PowerModel are analysed as `analyze --db` analyses a
// study (RM-ANOVA with the sphericity correction, Tukey-adjusted pairwise comparisons,
// Friedman and Bonferroni-adjusted Wilcoxon tests per questionnaire item), and the share of
// significant results is the power, with its Monte Carlo standard error and 95 % interval.
// exact_power gives the ANOVA effects' and contrasts' power from the noncentral F and t of
// data with exactly the model's moments (as Superpower's ANOVA_exact).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/power/power_model.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "core/util/portable_random.h"

namespace handlab::power {

// Which p an ANOVA effect with more than one numerator df is judged by.
enum class SphericityCorrection { kAuto, kNone, kGreenhouseGeisser, kHuynhFeldt };

struct PowerOptions {
  std::vector<int> n;  // participants, each >= 3
  int sims = 1000;
  double alpha = 0.05;
  std::uint64_t seed = 1;
  int threads = 1;  // results do not depend on it
  // kAuto: Greenhouse-Geisser where Mauchly's test rejects sphericity at alpha, as the study
  // report decides.
  SphericityCorrection correction = SphericityCorrection::kAuto;
};

struct PowerEstimate {
  std::string name;
  std::vector<double> power, mc_se, lower, upper;  // per N; lower/upper: 95 % (Wilson)
};

struct PowerReport {
  std::vector<int> n;
  int sims = 0;  // 0: exact
  double alpha = 0.05;
  std::vector<PowerEstimate> effects;    // ANOVA effects as analyze names them; then items
  std::vector<PowerEstimate> contrasts;  // "effect: a - b"; then items' Wilcoxon pairs
  std::vector<int> warnings;             // per N: simulations whose analysis warned
  std::vector<std::string> warning_examples;
  std::vector<double> seconds;  // per N, wall-clock
  std::vector<std::string> notes;
};

// The smallest N of the report whose power reaches `target`.
std::optional<int> n_for_target(const PowerReport& report, const PowerEstimate& e, double target);

// One simulated study: participants x cells (NaN: a trial without a result), the
// participants' covariate values, and per item participants x conditions answers.
struct SimulatedData {
  Eigen::MatrixXd cells;
  Eigen::MatrixXd covariates;
  std::vector<Eigen::MatrixXd> items;
};
SimulatedData simulate_data(const PowerModel& model, int n, util::PortableRandom& random);

// progress(done, total) after each N's simulations, from the calling thread.
PowerReport simulate_power(const PowerModel& model, const PowerOptions& options,
                           const std::function<void(int, int)>& progress = {});

// A planned contrast's name: "effect: a - b", with " | factor level" for a by-group.
std::string contrast_name(const stats::PairwiseContrast& contrast);

// The p an effect is judged by under `correction` (kAuto: the report's rule), and the factor
// its df take with it (the correction's epsilon; 1 uncorrected).
struct JudgedP {
  double p = 0.0;
  double df_scale = 1.0;
};
JudgedP judged(const stats::AnovaEffect& effect, SphericityCorrection correction, double alpha);
inline double judged_p(const stats::AnovaEffect& effect, SphericityCorrection correction,
                       double alpha) {
  return judged(effect, correction, alpha).p;
}

// A report of `n.size()` values of N for these effects and contrasts, counts to come.
PowerReport empty_report(const std::vector<std::string>& effects,
                         const std::vector<std::string>& contrasts, const std::vector<int>& n,
                         int sims, double alpha);
// Of the report's `sims` studies at its N number `k`: how many rejected each effect and
// contrast (in the report's order) and how many warned; sets the powers, Monte Carlo SEs and
// 95 % Wilson intervals. The model's and the pipeline's simulations share it.
void set_counts(PowerReport& report, std::size_t k, const std::vector<long>& effect_hits,
                const std::vector<long>& contrast_hits, int warnings, double seconds);

// The ANOVA effects (sphericity assumed) and the Tukey contrasts, without simulation. Items
// have no exact answer here; with missing trials, N is the expected count of participants
// with every cell.
PowerReport exact_power(const PowerModel& model, const PowerOptions& options);

}  // namespace handlab::power
