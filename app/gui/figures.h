// The study's figures drawn with QPainter, so that one code path serves the app's views and
// any QPaintDevice (QImage, QSvgGenerator, QPdfWriter): completion time per condition
// (mean ± SE), time per repetition by a factor, questionnaire medians and ranges.
// Greyscale-readable: levels differ by fill pattern and line style as well as by shade.
#pragma once

#include <QRectF>
#include <QString>

#include "studies/analysis/study_database_analysis.h"

class QPainter;

namespace handlab::gui {

// Mean ± SE of completion time per condition (the protocol's factors).
void paint_time_by_condition(QPainter& p, const QRectF& area,
                             const std::vector<studies::CellSummary>& cells);
// Mean ± SE per repetition, one line per level of `factor`.
void paint_time_by_repetition(QPainter& p, const QRectF& area, const QString& factor,
                              const std::vector<studies::CellSummary>& cells);
// Medians with their ranges per condition, one panel per item.
void paint_items(
    QPainter& p, const QRectF& area,
    const std::vector<std::pair<std::string, std::vector<studies::CellSummary>>>& items,
    int scale_points);

}  // namespace handlab::gui
