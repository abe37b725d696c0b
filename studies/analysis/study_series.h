// Several studies of one protocol side by side (`handlab-cli replications`): simulated
// studies of different seeds, or replications of a study. For each study what became of each
// condition's trials and every test its analysis made (study_tests.h); for each test the
// distribution of its statistic over the studies and how many rejected at alpha, which is the
// power the series shows; and beside them the values a published study reported.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "studies/analysis/cube_losses.h"
#include "studies/analysis/study_tests.h"

namespace handlab::studies {

// A study's reported test, named as study_tests names it. `value` and `p` are NaN when the
// publication did not give them; `p_below`: it gave only a bound ("p < .001").
struct PublishedTest {
  std::string name, statistic;
  double value = 0.0;
  std::vector<double> df;
  double p = 0.0;
  bool p_below = false;
};

struct PublishedStudy {
  std::string protocol;  // the protocol's name it reports a study of
  std::string source;
  int participants = 0;
  std::vector<PublishedTest> tests;
};

// A JSON file {"format": "handlab-published-results", "version": 1, "protocol", "source",
// "participants", "tests": [{"test", "statistic", "value", "df", "p" | "p_below"}]}.
PublishedStudy read_published_study(const std::string& path);

struct SeriesStudy {
  std::string path;
  int participants = 0;  // in the completion-time ANOVA
  std::vector<ConditionOutcome> conditions;
  CubeLosses losses;
  std::string warning;
};

struct SeriesTest {
  std::string name, statistic;
  std::string group;                          // StudyTest::group
  std::vector<double> value, p;               // per study; NaN where a study lacks the test
  int studies = 0;                            // that have it
  int rejected = 0;                           // of those, with p < alpha
  double median = 0.0, min = 0.0, max = 0.0;  // of the statistic over the studies with it
  double p_median = 0.0;
  std::optional<PublishedTest> published;
  // Where the published statistic falls in the series: the studies whose statistic is below
  // it (-1 when no value was published).
  int below_published = -1;
  // How large the effect is, so that studies agree or differ by size, not by p < alpha:
  // "pes" (partial eta squared) of an F test, "dz" (t / sqrt(n), n the people whose cell means it
  // compares) of a t test; empty for chi2 and V. Per study, then the median and the 2.5 and 97.5 %
  // quantiles (type 7) over the studies with it.
  std::string effect;
  std::vector<double> effect_value;
  double effect_median = 0.0, effect_low = 0.0, effect_high = 0.0;
  // The published test's effect and its 95 % interval from the noncentral F or t (NaN where
  // it gave no value or dfs), and how many studies' effects fall inside that interval.
  double published_effect = 0.0, published_low = 0.0, published_high = 0.0;
  int within_published = -1;
};

struct StudySeries {
  std::string protocol, protocol_sha256;
  double alpha = 0.05;
  std::vector<SeriesStudy> studies;
  std::vector<std::string> conditions;
  std::vector<SeriesTest> tests;  // in the order the first study that has each names them
  std::optional<PublishedStudy> published;
  std::vector<std::string> published_unmatched;  // published tests no study made
};

struct SeriesOptions {
  double alpha = 0.05;
  power::SphericityCorrection correction = power::SphericityCorrection::kAuto;
  std::optional<PublishedStudy> published;
  // Keep only these tests (by name), in this order; empty: every test.
  std::vector<std::string> only;
};

// Throws std::runtime_error when the studies are not of one protocol (its hash), when a
// published study is of another protocol, or when `only` names a test no study made.
StudySeries summarize_series(const std::vector<std::string>& paths, const SeriesOptions& options);

// Markdown tables: the studies, the share of trials completed per condition, the share that lost
// the cube per condition and per repetition (dropped, grasped again), and the tests,
// one table for each analysis they come from (statistic and p per study, median, range,
// rejections, the published value and how many studies fall below it).
void write_series_markdown(const StudySeries& series, std::ostream& out);
void write_series_json(const StudySeries& series, std::ostream& out);

}  // namespace handlab::studies
