#include "app/report/figure_marker.h"

#include <QPainter>

namespace handlab::report {

void draw_marker(QPainter& p, int shape, QPointF at, double radius) {
  const double r = radius;
  switch (shape % 4) {
    case 0:
      p.drawEllipse(at, r, r);
      break;
    case 1:
      p.drawRect(QRectF(at.x() - r, at.y() - r, 2 * r, 2 * r));
      break;
    case 2: {
      const QPointF triangle[] = {
          {at.x(), at.y() - r * 1.2}, {at.x() - r, at.y() + r}, {at.x() + r, at.y() + r}};
      p.drawPolygon(triangle, 3);
      break;
    }
    default: {
      const QPointF diamond[] = {{at.x(), at.y() - r * 1.3},
                                 {at.x() + r * 1.3, at.y()},
                                 {at.x(), at.y() + r * 1.3},
                                 {at.x() - r * 1.3, at.y()}};
      p.drawPolygon(diamond, 4);
    }
  }
}

}  // namespace handlab::report
