// A figure drawn with QPainter written as SVG (QSvgGenerator) or PNG (QImage) by one code
// path, chosen by the file's extension. Needs a QGuiApplication.
#pragma once

#include <functional>
#include <string>

#include <QPainter>
#include <QSize>

namespace handlab::report {

// Paints `size` pixels with `paint` into `path` (.svg or .png); throws std::runtime_error for
// another extension or a file that cannot be written.
void write_figure_file(const std::string& path, QSize size, const std::string& title,
                       const std::function<void(QPainter&, const QRectF&)>& paint);

}  // namespace handlab::report
