// A study's report written to a folder: report.html (self-contained, figures inline as SVG)
// and report.pdf (A4, vector figures, page numbers), as `handlab-cli report` and the app's
// File > Export Report... write them. Needs a QGuiApplication (the offscreen platform will
// do: no display is needed).
#pragma once

#include <string>

#include "studies/report/report_document.h"

namespace handlab::report {

struct ReportRequest {
  std::string database, folder;
  bool html = true, pdf = true;
  studies::ReportOptions options;
};

struct ReportFiles {
  std::string html, pdf;  // the paths written (empty: not asked for)
  int pdf_pages = 0;
  std::vector<std::string> not_computed;  // what the report says it could not compute
};

ReportFiles write_report(const ReportRequest& request);

}  // namespace handlab::report
