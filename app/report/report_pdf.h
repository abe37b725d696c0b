// The report as a PDF: A4, the figures as vectors (QPainter on QPdfWriter, the same figure code
// as the app and the HTML), tables in APA style split across pages with their header repeated,
// page numbers in the footer.
#pragma once

#include <QString>

#include "studies/report/report_document.h"

namespace handlab::report {

// Returns the number of pages written; throws std::runtime_error when the file cannot be made.
int write_report_pdf(const studies::ReportDocument& document,
                     const studies::StudyDatabaseAnalysis& analysis, const QString& path);

}  // namespace handlab::report
