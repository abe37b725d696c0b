#include "app/report/report_files.h"

#include <filesystem>
#include <stdexcept>

#include "app/report/report_figures.h"
#include "app/report/report_pdf.h"
#include "core/util/output_file.h"

namespace handlab::report {

ReportFiles write_report(const ReportRequest& request) {
  const studies::StudyDatabaseAnalysis analysis = studies::analyze_study_database(request.database);
  const studies::ReportDocument document = studies::build_report(analysis, request.options);
  util::make_output_folder(request.folder);
  ReportFiles files;
  if (!analysis.completion_time_not_computed.empty())
    files.not_computed.push_back("completion time: " + analysis.completion_time_not_computed);
  for (const auto& v : analysis.participant_variables)
    if (!v.result) files.not_computed.push_back(v.variable + ": " + v.not_computed);
  if (!analysis.questionnaire_not_computed.empty())
    files.not_computed.push_back("questionnaire: " + analysis.questionnaire_not_computed);
  const std::filesystem::path folder(request.folder);
  if (request.html) {
    files.html = (folder / "report.html").string();
    util::write_output(files.html, [&](std::ostream& out) {
      studies::write_report_html(
          document,
          [&](const studies::ReportFigure& f) { return figure_svg(f, analysis, document); }, out);
    });
  }
  if (request.pdf) {
    files.pdf = (folder / "report.pdf").string();
    files.pdf_pages = write_report_pdf(document, analysis, QString::fromStdString(files.pdf));
  }
  return files;
}

}  // namespace handlab::report
