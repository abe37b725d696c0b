#include "app/report/figure_file.h"

#include <stdexcept>

#include <QBuffer>
#include <QImage>
#include <QSvgGenerator>

#include "core/util/output_file.h"

namespace handlab::report {

void write_figure_file(const std::string& path, QSize size, const std::string& title,
                       const std::function<void(QPainter&, const QRectF&)>& paint) {
  const QString file = QString::fromStdString(path);
  const QRectF area(QPointF(0, 0), QSizeF(size));
  // A stream (standard output, /dev/null, a pipe) has no extension to choose by: SVG, text.
  const bool stream = !file.endsWith(".png", Qt::CaseInsensitive) && util::is_stream_output(path);
  if (file.endsWith(".svg", Qt::CaseInsensitive) || stream) {
    QByteArray bytes;
    QBuffer buffer(&bytes);
    QSvgGenerator svg;
    svg.setOutputDevice(&buffer);
    svg.setSize(size);
    svg.setViewBox(QRect(QPoint(0, 0), size));
    svg.setTitle(QString::fromStdString(title));
    {
      QPainter p(&svg);
      paint(p, area);
    }
    util::write_output_bytes(path, std::string_view(bytes.constData(), std::size_t(bytes.size())));
  } else if (file.endsWith(".png", Qt::CaseInsensitive)) {
    QImage image(size, QImage::Format_ARGB32);
    {
      QPainter p(&image);
      paint(p, area);
    }
    write_png_file(path, image);
  } else {
    throw std::runtime_error(path +
                             ": a figure is written as .svg or .png (or as SVG to - or a "
                             "pipe)");
  }
}

void write_png_file(const std::string& path, const QImage& image) {
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  if (!image.save(&buffer, "PNG"))
    throw util::OutputError("cannot write " + path + ": PNG encoding failed");
  util::write_output_bytes(path, std::string_view(bytes.constData(), std::size_t(bytes.size())));
}

}  // namespace handlab::report
