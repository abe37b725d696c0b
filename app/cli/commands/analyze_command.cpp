// handlab-cli analyze: repeated-measures ANOVA with post hoc tests, or Friedman and
// Wilcoxon tests, on a long-format CSV file; numbers equal to R's afex, emmeans and stats.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

#include "analysis/report/analysis_output.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_store.h"
#include "core/util/output_file.h"
#include "studies/analysis/study_database_analysis.h"

namespace handlab::cli {
namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) items.push_back(item);
  return items;
}

// The study's own analysis on its database: completion time by every factor and the
// repetition (RM-ANOVA with post hoc tests), then Friedman and Wilcoxon tests of the
// questionnaire items across the conditions. Skipped trials are left out; participants
// without every cell are dropped and named.
int analyze_database(const std::string& path, const std::string& json_out) {
  const studies::StudyDatabaseAnalysis analysis = studies::analyze_study_database(path);
  if (json_out != "-") studies::write_study_analysis_text(analysis, path, std::cout);
  if (!json_out.empty())
    util::write_output(
        json_out, [&](std::ostream& out) { studies::write_study_analysis_json(analysis, out); });
  return 0;
}

}  // namespace

namespace {

std::vector<OptionSpec> analyze_options() {
  return {
      {"csv", "FILE", "long-format data: one row per observation, with a header"},
      {"db", "DB",
       "a study database: run the study's analysis (completion time ANOVA, "
       "questionnaire Friedman/Wilcoxon)"},
      {"subject", "COL", "participant id column"},
      {"dv", "COL", "dependent variable (numeric) for the ANOVA"},
      {"within", "A,B,...", "within-participant factors (levels in order of first appearance)"},
      {"between", "C,...", "between-participant factors (sum-to-zero contrasts)"},
      {"covariate", "D,...", "numeric between-participant covariates, centred on their mean"},
      {"observed", "C,...",
       "measured (not manipulated) between variables, for generalised eta squared"},
      {"posthoc", "EFFECT",
       "cells to compare, e.g. manipulation:strategy, or strategy|repetition for "
       "strategy at each repetition; repeatable; default: every within effect",
       "", true},
      {"nonparametric", "ITEM,...",
       "Friedman and pairwise Wilcoxon tests of these columns instead"},
      {"json", "OUT", "write every number as JSON to OUT (- for standard output)"},
  };
}

CommandHelp analyze_help() {
  return {"analyze",
          {"csv subject dv within [between] [covariate] [observed] [posthoc] [json]",
           "csv subject within nonparametric [json]", "db [json]"},
          "Repeated-measures ANOVA (type 3, as afex::aov_ez) with Mauchly's test, Greenhouse-\n"
          "Geisser and Huynh-Feldt corrections, and pairwise comparisons of cell means (as\n"
          "emmeans on afex's multivariate model: Tukey, Bonferroni, Holm); or, with\n"
          "--nonparametric, Friedman's test and Bonferroni/Holm-adjusted Wilcoxon signed-rank\n"
          "tests between all conditions for each item. Prints an APA-style report."};
}

}  // namespace

int run_analyze(const std::vector<std::string>& argv) {
  const Arguments args(analyze_options(), argv);
  if (args.help_requested()) return print_help(analyze_help(), args);
  if (args.has("db")) {
    if (args.has("csv")) throw UsageError("give --csv or --db, not both");
    return analyze_database(args.text("db"), args.text("json"));
  }
  args.require({"csv", "subject", "within"});

  analysis::AnalysisRequest request;
  request.design.subject = args.text("subject");
  request.design.within = split_list(args.text("within"));
  request.design.between = split_list(args.text("between"));
  request.design.covariates = split_list(args.text("covariate"));
  request.design.observed = split_list(args.text("observed"));
  request.posthoc = args.all("posthoc");
  request.nonparametric_items = split_list(args.text("nonparametric"));
  if (request.nonparametric_items.empty()) {
    if (!args.has("dv")) throw UsageError("--dv is required (or --nonparametric)");
    request.design.dv = args.text("dv");
  } else if (!request.design.between.empty() || !request.design.covariates.empty()) {
    throw UsageError(
        "--nonparametric compares within conditions only: drop --between and --covariate");
  }

  const analysis::LongTable table = analysis::LongTable::read_csv(args.text("csv"));
  const analysis::AnalysisReport report = analysis::run_analysis(table, request);

  const std::string json_out = args.text("json");
  if (json_out != "-") analysis::write_text(report, std::cout);
  if (!json_out.empty()) {
    util::write_output(json_out, [&](std::ostream& out) { analysis::write_json(report, out); });
  }
  return 0;
}

}  // namespace handlab::cli
