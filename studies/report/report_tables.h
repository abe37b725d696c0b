// The report's tables and sentences of one analysis, wherever in the analysis JSON it sits
// (`root`, a JSON pointer such as "/completion_time"): the RM-ANOVA's table and the sentence of
// a significant effect; Friedman's tests, their sentences with the significant Wilcoxon pairs,
// and the Wilcoxon table. The completion time, its analysis without the timed-out trials, the
// success rates and the questionnaire are all written by these.
#pragma once

#include <string>

#include "analysis/report/study_analysis.h"
#include "studies/report/report_document.h"

namespace handlab::studies {

// Effect, df, F, p, η²G, ε (GG), Mauchly's W and p; df and p Greenhouse–Geisser corrected where
// Mauchly's test rejects sphericity. The caption is left to the caller.
ReportTable anova_table(const analysis::AnalysisReport& report, const std::string& root);

// Whether Mauchly's test rejects sphericity for the effect (so its df and p are corrected), and
// whether its p, so judged, is below .05.
bool sphericity_corrected(const stats::AnovaEffect& effect);
bool anova_significant(const stats::AnovaEffect& effect);

// "There was a significant main effect of Manipulation on completion time, F(1, 19) = ...";
// `key` is the effect's JSON pointer with a trailing '/'.
ReportLine anova_sentence(const std::string& key, const stats::AnovaEffect& effect, bool corrected,
                          const std::string& dv);

// Item, χ², df, p, Kendall's W, n.
ReportTable friedman_table(const analysis::AnalysisReport& report, const std::string& root);
// "<Item>: the scores differed significantly across conditions, χ²(3, N = 20) = ..." with the
// Wilcoxon pairs that are significant after Bonferroni's adjustment.
ReportLine friedman_sentence(const analysis::AnalysisReport& report, std::size_t item,
                             const std::string& root, const std::string& what);
// Item, contrast, V, n, p, p (Bonferroni).
ReportTable wilcoxon_table(const analysis::AnalysisReport& report, const std::string& root);

}  // namespace handlab::studies
