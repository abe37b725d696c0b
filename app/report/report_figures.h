// The report's figures, drawn with QPainter so that one code path serves the app's Analysis
// view, the PDF (QPdfWriter: vectors), the HTML (QSvgGenerator) and pictures (QImage), as the
// paper's Figures 3.5-3.8: completion time per condition with the planned comparisons'
// brackets, per repetition, against hand length, and the questionnaire's medians and ranges.
// Readable in greyscale: levels differ by fill pattern, line style and marker as well as shade.
#pragma once

#include <string>

#include <QRectF>

#include "studies/report/report_document.h"

class QPainter;

namespace handlab::report {

// The height a figure wants for a width (its panels' proportions and how many rows of them
// the study's design needs).
double figure_height(studies::FigureKind kind, const studies::StudyDatabaseAnalysis& analysis,
                     double width);

// Paints `figure` into `area` with the painter's font (its size sets the figure's text).
void paint_figure(QPainter& p, const QRectF& area, const studies::ReportFigure& figure,
                  const studies::StudyDatabaseAnalysis& analysis,
                  const studies::ReportDocument& document);

// The figure as SVG markup for inlining in HTML (no XML prolog), `width` px wide.
std::string figure_svg(const studies::ReportFigure& figure,
                       const studies::StudyDatabaseAnalysis& analysis,
                       const studies::ReportDocument& document, int width = 720);

}  // namespace handlab::report
