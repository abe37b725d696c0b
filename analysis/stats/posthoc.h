// Estimated marginal means and pairwise comparisons of within cells, averaged over the
// other within factors, as emmeans computes them on afex's multivariate model: every
// contrast is a t test on participants' contrast scores, df = participants - parameters
// (N - 1 in a purely within design), between groups weighted equally, covariates at their mean.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "analysis/stats/rm_data.h"

namespace handlab::stats {

struct PosthocSpec {
  std::vector<std::string> factors;  // compared cells: combinations of these within factors
  std::vector<std::string> by;       // simple effects: compare within each level of these
  // Contrast labels with levels as emmeans shows them ("X1" for level "1"), to compare with
  // R; false: as the data names them.
  bool r_level_names = true;
  // "manipulation:strategy" or "strategy|repetition" (simple effects of strategy at each
  // repetition); throws DataError for names that are not within factors.
  static PosthocSpec parse(const std::string& text, const RmData& data);
  std::string effect() const;  // factors joined by ':'
};

struct MarginalMean {
  std::vector<std::pair<std::string, std::string>> at;  // factor -> level, spec then by factors
  double estimate, se, df, lower_cl, upper_cl;          // 95% confidence interval
};

struct PairwiseContrast {
  std::string effect;
  std::string contrast;  // emmeans's label, e.g. "Gross Naive - Fine Naive"
  std::vector<std::pair<std::string, std::string>> by;  // the by-group, for simple effects
  std::vector<std::pair<std::string, std::string>> first, second;  // the cells compared
  double estimate, se, df, t;
  double p_none, p_tukey, p_bonferroni, p_holm;  // adjusted within the by-group (emmeans)
  double p_bonferroni_all, p_holm_all;           // adjusted over every contrast of the spec
};

struct PosthocResult {
  std::vector<MarginalMean> means;
  std::vector<PairwiseContrast> contrasts;
};

PosthocResult pairwise_comparisons(const RmData& data, const PosthocSpec& spec);

// emmeans shows levels as afex names them: a level that is not a syntactic R name (e.g. "1")
// gets an "X" prefix.
std::string emmeans_level_label(const std::string& level);

}  // namespace handlab::stats
