// The tests one study's analysis made, one row each with its statistic, degrees of freedom
// and the p it is judged by, named so that the studies of a series line up: ANOVA effects as
// `analyze` names them ("strategy:manipulation"), the cells of the protocol's factors compared
// pairwise ("strategy:manipulation: naive fine - ours fine", Tukey), and per questionnaire
// item Friedman's test ("precision (Friedman)") and the pairwise Wilcoxon tests
// ("precision: naive fine - ours fine (Wilcoxon)", Bonferroni); each factor's levels on the
// first repetition ("strategy:repetition: naive 1 - ours 1", Tukey); the effects that involve a
// participant variable in its follow-up ANOVA ("hand_length:manipulation (covariate)",
// "vr_experience:strategy (between)"); the completion time's effects and contrasts again with
// the timed-out trials left out ("manipulation (timeouts left out)"); and the success rates'
// Friedman and Wilcoxon tests ("success_rate (Friedman)"). A pair of cells is always
// written in the protocol's order of levels (the first factor's first), whichever way the
// data happened to order them, and its statistic's sign follows: t is the first cell's mean
// minus the second's.
#pragma once

#include <string>
#include <vector>

#include "analysis/power/power_analysis.h"
#include "studies/analysis/study_database_analysis.h"

namespace handlab::studies {

struct StudyTest {
  std::string name;
  std::string statistic;   // "F", "t", "chi2" or "V"
  double value = 0.0;      // NaN when the test has none (every difference zero)
  std::vector<double> df;  // F: numerator and denominator (corrected when p is); t, chi2: one
  double p = 0.0;          // as judged: the sphericity correction, Tukey, Bonferroni
  bool contrast = false;   // a comparison of two cells (t, V), not an omnibus test
  std::string group;       // the analysis it belongs to: one of the kTests* names below
  int participants = 0;    // t: the people its cells' means are of (d_z's n); 0: not known
};

// The analyses the tests come from, in the order they are listed.
inline constexpr const char* kTestsTimeoutsAtLimit = "completion time, timeouts at the limit";
inline constexpr const char* kTestsTimeoutsLeftOut = "completion time, timeouts left out";
inline constexpr const char* kTestsSuccess = "success";
inline constexpr const char* kTestsQuestionnaire = "questionnaire";

struct StudyTests {
  std::vector<StudyTest> tests;  // effects, contrasts, then items
  std::string warning;           // what could not be analysed, or who was left out
};

// The ANOVA effects judged with `correction` at `alpha` (kAuto: Greenhouse-Geisser where
// Mauchly's test rejects sphericity, as the study report decides).
StudyTests study_tests(const StudyDatabaseAnalysis& analysis,
                       power::SphericityCorrection correction, double alpha);

}  // namespace handlab::studies
