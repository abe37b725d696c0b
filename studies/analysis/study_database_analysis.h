// The analysis of a study database, as `handlab-cli analyze --db`, `handlab-cli report` and
// the app's Analysis view run it: the completion-time RM-ANOVA over the protocol's factors and
// repetition with its post hoc tests, the follow-ups with each participant variable (age and
// hand length as covariates, VR experience between participants), Friedman and Wilcoxon tests
// per questionnaire item, who took part and what the data hold, and the cell summaries the
// figures draw. Levels are named as the protocol names them.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/report/study_analysis.h"
#include "core/store/study_store.h"
#include "studies/analysis/condition_outcomes.h"
#include "studies/analysis/cube_losses.h"
#include "studies/analysis/timeout_analyses.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

// One point of a figure or one row of a descriptives table: a cell of some factors.
struct CellSummary {
  std::vector<std::string> levels;  // per factor of the summary
  int n = 0;                        // participants
  // Of the participants' means in the cell.
  double mean = 0, sd = 0, se = 0, median = 0;
  // The within-participant SE (Cousineau 2005 with Morey's 2008 correction over the cells of
  // the summary): each participant's means moved to the grand mean before the SE is taken.
  double se_within = 0;
  double min = 0, max = 0;  // of the values themselves
};

// A participant's mean in each level of a factor, against their hand length (Fig. 3.7).
struct HandLengthPoint {
  std::string participant, level;
  double hand_length_cm = 0, mean = 0;
};

struct ParticipantSummary {
  int enrolled = 0, simulated = 0;
  int analysed = 0;  // in the completion-time ANOVA
  int age_n = 0;     // participants with an age
  double age_mean = 0, age_sd = 0, age_min = 0, age_max = 0;
  double hand_cm_mean = 0, hand_cm_sd = 0, hand_cm_min = 0, hand_cm_max = 0;
  std::vector<std::pair<std::string, int>> sex, handedness, vr_experience;  // counts
  // Per between-participants factor of the protocol: participants per level, in its order.
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, int>>>> groups;
};

struct DataQuality {
  int planned = 0;  // scheduled trials, practice excluded
  int completed = 0, timeouts = 0, skipped = 0, not_run = 0;
  std::vector<ConditionOutcome> by_condition;     // in the protocol's order of conditions
  CubeLosses losses;                              // the trials that lost the cube
  int attempts_aborted = 0, attempts_redone = 0;  // attempts of scheduled trials
  int practice_run = 0;
  std::int64_t frames = 0;
  // Who an analysis left out, and why ("completion time: lacks a result in some cell").
  std::vector<std::pair<std::string, std::string>> left_out;
};

// A follow-up of the completion-time ANOVA over the protocol's factors (repetitions averaged)
// with one participant variable: a covariate (centred) or a between-participants factor.
struct ParticipantVariableAnalysis {
  std::string variable;  // "age", "hand_length", "vr_experience"
  bool between = false;  // a factor, not a covariate
  std::optional<analysis::AnalysisReport> result;
  std::string not_computed;  // why, when there is no result
};

struct StudyDatabaseAnalysis {
  store::StudyInfo study;
  // A simulated study merged from only some of its parts says so (partial()).
  store::StudyCompleteness completeness;
  Protocol protocol;
  ParticipantSummary participants;
  DataQuality quality;
  // Empty when no participant finished a trial; `not_computed` says why.
  std::optional<analysis::AnalysisReport> completion_time;
  std::string completion_time_not_computed;
  // The completion time the two other ways (timeout_analyses.h): the timed-out trials left
  // out, and success as its own outcome. `completion_time` keeps them at the trial's limit.
  OutcomeAnalysis time_without_timeouts;
  OutcomeAnalysis success;
  std::vector<ParticipantVariableAnalysis> participant_variables;
  std::optional<analysis::AnalysisReport> questionnaire;
  std::string questionnaire_not_computed;
  // Completion time per condition (the protocol's factors), per repetition by each factor,
  // and against hand length by each factor.
  std::vector<CellSummary> time_by_condition;
  std::vector<std::pair<std::string, std::vector<CellSummary>>> time_by_repetition;
  std::vector<std::pair<std::string, std::vector<HandLengthPoint>>> time_by_hand_length;
  // Per questionnaire item, per condition: medians and ranges of the answers.
  std::vector<std::pair<std::string, std::vector<CellSummary>>> items_by_condition;
};

// Any study file the store opens: what cannot be computed yet (no trials, one participant, a
// condition nobody finished, no questionnaire) is said in the *_not_computed fields.
StudyDatabaseAnalysis analyze_study_database(const std::string& path);

void write_study_analysis_text(const StudyDatabaseAnalysis& analysis, const std::string& path,
                               std::ostream& out);
// Keys: study (with partial, planned_participants, missing_places), participants, data_quality,
// completion_time (null with completion_time_not_computed), completion_time_without_timeouts and
// success (each null with its *_not_computed), condition_descriptives, participant_variables,
// questionnaire (null with questionnaire_not_computed).
void write_study_analysis_json(const StudyDatabaseAnalysis& analysis, std::ostream& out);

}  // namespace handlab::studies
