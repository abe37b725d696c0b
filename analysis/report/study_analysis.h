// One analysis request over a long table, as `handlab-cli analyze` runs it: either the
// parametric path (RM-ANOVA, post hoc, descriptives) or the nonparametric one (Friedman
// and pairwise Wilcoxon per item).
#pragma once

#include <string>
#include <vector>

#include "analysis/data/long_table.h"
#include "analysis/stats/descriptives.h"
#include "analysis/stats/nonparametric.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"

namespace handlab::analysis {

struct AnalysisRequest {
  stats::RmDesignSpec design;        // subject, dv, within, between, covariates, observed
  std::vector<std::string> posthoc;  // effects ("a:b", "a|b"); empty: every within effect
  std::vector<std::string> nonparametric_items;  // non-empty: the nonparametric path
  bool r_level_names = true;  // post hoc labels as emmeans shows levels ("X1"), or as given
};

struct CellDescriptives {
  std::vector<std::pair<std::string, std::string>> cell;  // factor -> level
  stats::Descriptives d;
};

struct FriedmanItem {
  std::string dv;
  stats::FriedmanResult result;
  std::vector<std::string> dropped_subjects;
};

struct WilcoxonPair {
  std::string dv, contrast;
  std::vector<std::string> first, second;  // the conditions' levels, one per factor
  stats::WilcoxonResult result;
  double p_bonferroni, p_holm;
};

struct AnalysisReport {
  AnalysisRequest request;
  std::string source;
  int n_subjects = 0;
  std::vector<std::string> dropped_subjects;
  std::vector<std::string> warnings;
  std::vector<double> covariate_means;
  stats::AnovaResult anova;
  std::vector<stats::PosthocResult> posthoc;
  std::vector<CellDescriptives> descriptives;
  std::vector<FriedmanItem> friedman;
  std::vector<WilcoxonPair> wilcoxon;
  bool nonparametric() const { return !request.nonparametric_items.empty(); }
};

AnalysisReport run_analysis(const LongTable& table, const AnalysisRequest& request);

}  // namespace handlab::analysis
