// A figure drawn with QPainter written as SVG (QSvgGenerator) or PNG (QImage) by one code
// path, chosen by the file's extension. Needs a QGuiApplication.
#pragma once

#include <functional>
#include <string>

#include <QImage>
#include <QPainter>
#include <QSize>

namespace handlab::report {

// Paints `size` pixels with `paint` into `path` (.svg or .png; SVG to "-", a device or a pipe)
// by util::write_output's rules; throws std::runtime_error for another extension or an output
// that cannot be written.
void write_figure_file(const std::string& path, QSize size, const std::string& title,
                       const std::function<void(QPainter&, const QRectF&)>& paint);

// Writes `image` to `path` as PNG by util::write_output's rules; throws util::OutputError.
void write_png_file(const std::string& path, const QImage& image);

}  // namespace handlab::report
