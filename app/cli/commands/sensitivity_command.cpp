// handlab-cli sensitivity: the participant model's global sensitivity analysis (Morris's
// elementary effects) on whole simulated studies.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/world_option.h"
#include "core/util/output_file.h"
#include "studies/sensitivity/model_sensitivity.h"
#ifdef HANDLAB_WITH_REPORT
#include "app/cli/gui_application.h"
#include "app/report/sensitivity_figure.h"
#endif

namespace handlab::cli {
namespace {

// Runs the analysis the options ask for, its progress on standard error.
studies::SensitivityReport run_analysis(const Arguments& args, const studies::Protocol& protocol) {
  args.require({"work"});
  studies::SensitivityOptions options;
  options.work_dir = args.text("work");
  options.participants = int(args.integer("participants"));
  if (options.participants < 2) throw UsageError("--participants must be 2 or more");
  options.seed = args.seed("seed");
  options.trajectories = int(args.integer("trajectories"));
  options.levels = int(args.integer("levels"));
  if (options.trajectories < 2) throw UsageError("--trajectories must be 2 or more");
  if (options.levels < 2 || options.levels % 2) throw UsageError("--levels must be even");
  options.design_seed = args.seed("design-seed");
  options.jobs = int(args.integer("jobs"));
  if (options.jobs <= 0) options.jobs = int(std::max(1u, std::thread::hardware_concurrency()));
  options.world = world_kind(args);
  if (!args.all("output").empty()) options.outputs = args.all("output");
  options.only = args.all("parameter");
  // An output on standard output is all that is printed there.
  const bool quiet = args.text("json") == "-" || args.text("plot") == "-";
  try {
    return studies::run_model_sensitivity(
        protocol, options, [&](const studies::SensitivityProgress& p) {
          if (!quiet)
            std::fprintf(stderr, "point %d/%d  %.0f s\n", p.points_done, p.points, p.seconds);
        });
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

namespace {

std::vector<OptionSpec> sensitivity_options() {
  return {
      {"protocol", "FILE", "the study protocol (JSON)"},
      {"work", "DIR", "where each point's study database is written while it is analysed"},
      {"participants", "N", "participants in each study", "20"},
      {"seed", "S", "the population seed, the same at every point", "1"},
      {"trajectories", "R", "Morris trajectories (R (k + 1) studies for k parameters)", "4"},
      {"levels", "P", "grid levels of each parameter's range (even)", "4"},
      {"design-seed", "D", "the seed of the trajectories", "1"},
      {"jobs", "J", "sessions run side by side (threads; default: the machine's cores)", "0"},
      world_option(),
      {"output", "TEST",
       "a test whose statistic is analysed, as replications names it; repeatable (default: "
       "the within factors' interaction F, the repetition F, and the t of the first factor's "
       "first two levels at the others' last: in the study, fine Naive - Ours)",
       "", true},
      {"parameter", "NAME",
       "vary only this parameter (the others stay at the model's values); repeatable "
       "(default: every parameter of docs/simulated-participants.md's sensitivity table)",
       "", true},
      {"from", "JSON",
       "instead of running the analysis, take one run before (its --json) to print, draw or "
       "write again"},
      {"plot", "FILE", "draw mu* against sigma per output (.svg or .png)"},
      {"json", "OUT", "write every index and every point as JSON (- for standard output)"},
  };
}

CommandHelp sensitivity_help() {
  return {"sensitivity",
          {"protocol work [trajectories] [plot] [json] [options]", "protocol from [plot] [json]"},
          "How the simulated studies' conclusions hang on the participant model's parameters: a "
          "Morris design over the parameters' ranges (docs/simulated-participants.md), a whole "
          "simulated study at each point (the same population seed at every point), and per "
          "output test each parameter's mu* and sigma in the statistic's units over the "
          "parameter's range. Prints a Markdown table per output."};
}

}  // namespace

int run_sensitivity(const std::vector<std::string>& argv) {
  const studies::SensitivityOptions defaults;
  const Arguments args(sensitivity_options(), argv);
  if (args.help_requested()) return print_help(sensitivity_help(), args);
  args.require({"protocol"});
  if (args.has("from") && args.has("work"))
    throw UsageError("--from reads an analysis run before: it takes no --work");
  const studies::Protocol protocol = studies::read_protocol(args.text("protocol"));
  const studies::SensitivityReport report = args.has("from")
                                                ? studies::read_sensitivity_json(args.text("from"))
                                                : run_analysis(args, protocol);
  // An output on standard output is all that is printed there.
  if (args.text("json") != "-" && args.text("plot") != "-")
    studies::write_sensitivity_markdown(report, std::cout);
#ifdef HANDLAB_WITH_REPORT
  if (args.has("plot")) {
    ensure_gui_application();
    report::write_sensitivity_figure(
        report, "Sensitivity of " + protocol.name + " to the participant model", args.text("plot"));
  }
#else
  if (args.has("plot")) throw UsageError("--plot needs the report (built with Qt)");
#endif
  if (args.has("json"))
    util::write_output(args.text("json"),
                       [&](std::ostream& out) { studies::write_sensitivity_json(report, out); });
  return 0;
}

}  // namespace handlab::cli
