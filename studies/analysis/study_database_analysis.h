// The analysis of a study database, as `handlab-cli analyze --db` and the app's Analysis
// view run it: the completion-time RM-ANOVA over the protocol's factors and repetition with
// its post hoc tests, Friedman and Wilcoxon tests per questionnaire item, and the cell
// summaries the figures draw (the mean of participant means with its SE; questionnaire
// medians and ranges).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/report/study_analysis.h"
#include "core/store/study_store.h"

namespace handlab::studies {

// One point of a figure: a cell of some factors, over participants.
struct CellSummary {
  std::vector<std::string> levels;  // per factor of the summary
  int n = 0;                        // participants
  double mean = 0, se = 0;          // of participant means
  double median = 0, min = 0, max = 0;
};

struct StudyDatabaseAnalysis {
  store::StudyInfo study;
  analysis::AnalysisReport completion_time;
  std::optional<analysis::AnalysisReport> questionnaire;
  // Completion time per condition (the protocol's factors), and per repetition by each factor.
  std::vector<CellSummary> time_by_condition;
  std::vector<std::pair<std::string, std::vector<CellSummary>>> time_by_repetition;
  // Per questionnaire item, per condition: medians and ranges of the answers.
  std::vector<std::pair<std::string, std::vector<CellSummary>>> items_by_condition;
};

// Throws std::runtime_error when the database has no trial results yet.
StudyDatabaseAnalysis analyze_study_database(const std::string& path);

void write_study_analysis_text(const StudyDatabaseAnalysis& analysis, const std::string& path,
                               std::ostream& out);
void write_study_analysis_json(const StudyDatabaseAnalysis& analysis, std::ostream& out);

}  // namespace handlab::studies
