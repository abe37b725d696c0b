#include "app/report/figure_file.h"

#include <stdexcept>

#include <QImage>
#include <QSvgGenerator>

namespace handlab::report {

void write_figure_file(const std::string& path, QSize size, const std::string& title,
                       const std::function<void(QPainter&, const QRectF&)>& paint) {
  const QString file = QString::fromStdString(path);
  const QRectF area(QPointF(0, 0), QSizeF(size));
  if (file.endsWith(".svg", Qt::CaseInsensitive)) {
    QSvgGenerator svg;
    svg.setFileName(file);
    svg.setSize(size);
    svg.setViewBox(QRect(QPoint(0, 0), size));
    svg.setTitle(QString::fromStdString(title));
    QPainter p(&svg);
    paint(p, area);
  } else if (file.endsWith(".png", Qt::CaseInsensitive)) {
    QImage image(size, QImage::Format_ARGB32);
    {
      QPainter p(&image);
      paint(p, area);
    }
    if (!image.save(file)) throw std::runtime_error(path + ": cannot write");
  } else {
    throw std::runtime_error(path + ": a figure is written as .svg or .png");
  }
}

}  // namespace handlab::report
