// The completion time when some trials timed out, analysed the two other ways beside the
// main analysis (which keeps a timed-out trial at the trial's limit): with the timed-out trials
// left out, and with success as an outcome of its own. A timeout is a time only censored at
// the limit, so which way a study reads depends on how many trials end there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/data/long_table.h"
#include "analysis/report/study_analysis.h"

namespace handlab::studies {

struct OutcomeAnalysis {
  std::optional<analysis::AnalysisReport> result;
  std::string not_computed;  // why, when there is no result
};

// The RM-ANOVA over `factors` and repetition (and the `between` factors) of the completed
// trials alone (the rows of `trials` whose outcome is "success"); a participant without a
// completed trial in some condition and repetition is left out, as R's aov / afex leave them.
OutcomeAnalysis time_without_timeouts(const analysis::LongTable& trials,
                                      const std::vector<std::string>& factors,
                                      const std::vector<std::string>& between = {});

// Each participant's share of completed trials per condition (`success_rate`: completed of
// completed and timed out), compared across the conditions by Friedman's test with pairwise
// Wilcoxon signed-rank tests (Bonferroni), as the questionnaire's items are.
OutcomeAnalysis success_rates(const analysis::LongTable& trials,
                              const std::vector<std::string>& factors);

}  // namespace handlab::studies
