// handlab-cli report: the study's results section, tables and figures from its database, as
// one self-contained HTML file and an A4 PDF, with no display (Qt's offscreen platform).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/gui_application.h"
#include "app/report/report_files.h"

namespace handlab::cli {

namespace {

std::vector<OptionSpec> report_options() {
  return {
      {"db", "DB", "the study database"},
      {"out", "DIR", "the folder to write report.html and report.pdf into (made if missing)"},
      {"format", "html,pdf", "which files to write", "html,pdf"},
      {"error-bars", "se|within",
       "the figures' error bars: the SE of participants' means, or the within-participant SE "
       "(Cousineau-Morey)",
       "se"},
  };
}

CommandHelp report_help() {
  return {"report",
          {"db out [format] [error-bars]"},
          "Writes the study's results section from its database: study and protocol,\n"
          "participants, data quality, descriptives, the repeated-measures ANOVA (APA\n"
          "table), post hoc comparisons, the participant variables' ANOVAs, Friedman and\n"
          "Wilcoxon tests of the questionnaire, result sentences, and the paper's figures.\n"
          "Every number is the one `analyze --db DB --json` gives. No display needed."};
}

}  // namespace

int run_report(const std::vector<std::string>& argv) {
  const Arguments args(report_options(), argv);
  if (args.help_requested()) return print_help(report_help(), args);
  if (!args.has("db")) throw UsageError("name the study database (--db DB)");
  if (!args.has("out")) throw UsageError("name the folder to write into (--out DIR)");
  report::ReportRequest request;
  request.database = args.text("db");
  request.folder = args.text("out");
  request.html = request.pdf = false;
  std::stringstream formats(args.text("format"));
  for (std::string f; std::getline(formats, f, ',');) {
    if (f == "html")
      request.html = true;
    else if (f == "pdf")
      request.pdf = true;
    else if (!f.empty())
      throw UsageError("--format takes html, pdf or both (html,pdf), not '" + f + "'");
  }
  if (!request.html && !request.pdf) throw UsageError("--format names no file to write");
  const std::string bars = args.text("error-bars");
  if (bars == "within")
    request.options.error_bars = studies::ErrorBars::kWithinParticipant;
  else if (bars != "se")
    throw UsageError("--error-bars takes se or within, not '" + bars + "'");
  ensure_gui_application();
  const auto start = std::chrono::steady_clock::now();
  const report::ReportFiles files = report::write_report(request);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!files.html.empty()) std::cout << "wrote " << files.html << "\n";
  if (!files.pdf.empty())
    std::cout << "wrote " << files.pdf << " (" << files.pdf_pages << " pages)\n";
  for (const std::string& what : files.not_computed) std::cout << "not computed: " << what << "\n";
  std::printf("in %.1f s\n", seconds);
  return 0;
}

}  // namespace handlab::cli
