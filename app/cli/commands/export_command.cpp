// handlab-cli export: a study database's results as CSV for R, JASP or jamovi.
#include <filesystem>
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_store.h"
#include "core/util/output_file.h"
#include "studies/export/study_export.h"

namespace handlab::cli {

namespace {

std::vector<OptionSpec> export_options() {
  return {
      {"db", "DB", "the study database"},
      {"out", "DIR", "directory for trials.csv and questionnaire.csv (created if needed)"},
      {"frames", "",
       "also frames.csv: every logged step of those trials (cube, fingertips, aperture)"},
  };
}

CommandHelp export_help() {
  return {"export",
          {"db out [frames]"},
          "Writes trials.csv (one row per trial with a result: participant, covariates, block, "
          "order, factors, repetition, completion_time_s, outcome, grasps, drops) and "
          "questionnaire.csv (one column per item); with --frames, frames.csv (one row per "
          "logged step of those trials: time, task phase, the cube's centre, the contacts, the "
          "simulated thumb and index tips, their aperture, the tracked aperture; docs/study.md). "
          "Practice trials are left out."};
}

}  // namespace

int run_export(const std::vector<std::string>& argv) {
  const Arguments args(export_options(), argv);
  if (args.help_requested()) return print_help(export_help(), args);
  args.require({"db", "out"});
  store::StudyStore store(args.text("db"), store::StudyStore::Access::kReadOnly);
  const std::filesystem::path dir = args.text("out");
  util::make_output_folder(dir.string());
  util::write_output((dir / "trials.csv").string(),
                     [&](std::ostream& out) { studies::write_trials_csv(store, out); });
  util::write_output((dir / "questionnaire.csv").string(),
                     [&](std::ostream& out) { studies::write_questionnaire_csv(store, out); });
  std::cout << "wrote " << (dir / "trials.csv").string() << " and "
            << (dir / "questionnaire.csv").string();
  if (args.flag("frames")) {
    util::write_output((dir / "frames.csv").string(),
                       [&](std::ostream& out) { studies::write_frames_csv(store, out); });
    std::cout << " and " << (dir / "frames.csv").string();
  }
  std::cout << "\n";
  return 0;
}

}  // namespace handlab::cli
