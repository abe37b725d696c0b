// handlab-cli replications: several studies of one protocol side by side (simulated studies of
// different seeds, replications), each test's distribution over them and the published values.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/util/output_file.h"
#include "studies/analysis/study_series.h"

namespace handlab::cli {

namespace {

std::vector<OptionSpec> replications_options() {
  return {
      {"published", "FILE",
       "a published study's results to set beside them (e.g. "
       "studies/fine-manipulation-2021-published.json)"},
      {"test", "NAME", "show only this test (as the table names it); repeatable", "", true},
      {"alpha", "A", "the significance level", "0.05"},
      {"correction", "auto|none|gg|hf",
       "the p of effects with more than one df: auto = Greenhouse-Geisser where Mauchly's test "
       "rejects sphericity, as the study report decides",
       "auto"},
      {"json", "OUT", "write every number as JSON to OUT (- for standard output)"},
  };
}

CommandHelp replications_help() {
  return {"replications",
          {"DB... [published] [test] [json]"},
          "Analyses each study database as `analyze --db` does and sets the studies side by "
          "side: the share of each condition's scheduled trials completed, the share of each "
          "condition's and each repetition's trials that dropped the cube or grasped it again, "
          "and for every test "
          "(the ANOVA effects, the pairwise comparisons of the protocol's cells, each "
          "questionnaire item's Friedman and Wilcoxon tests) its statistic and p per study, "
          "their median and range, and in how many studies p < alpha (with simulated studies of "
          "one design, the power it has). Pairs of cells are named in the protocol's order of "
          "levels, so t is the first cell's mean minus the second's in every study. The studies "
          "must share one protocol. Prints Markdown tables."};
}

}  // namespace

int run_replications(const std::vector<std::string>& argv) {
  const Arguments args(replications_options(), argv, 1000);
  if (args.help_requested()) return print_help(replications_help(), args);
  if (args.positional().empty()) throw UsageError("give one or more study databases");
  studies::SeriesOptions options;
  options.alpha = args.number("alpha");
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be in (0, 1)");
  options.correction = sphericity_correction(args.text("correction"));
  if (args.has("published"))
    options.published = studies::read_published_study(args.text("published"));
  options.only = args.all("test");
  const studies::StudySeries series = studies::summarize_series(args.positional(), options);
  const std::string json_out = args.text("json");
  if (json_out != "-") studies::write_series_markdown(series, std::cout);
  if (!json_out.empty())
    util::write_output(json_out,
                       [&](std::ostream& out) { studies::write_series_json(series, out); });
  return 0;
}

}  // namespace handlab::cli
