#include "app/gui/figures.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <QObject>
#include <QPainter>
#include <QPainterPath>

namespace handlab::gui {
namespace {

const QColor kShades[] = {QColor(60, 60, 60), QColor(150, 150, 150), QColor(210, 210, 210),
                          QColor(100, 100, 100)};
const Qt::BrushStyle kPatterns[] = {Qt::SolidPattern, Qt::BDiagPattern, Qt::SolidPattern,
                                    Qt::CrossPattern};
const Qt::PenStyle kLines[] = {Qt::SolidLine, Qt::DashLine, Qt::DotLine, Qt::DashDotLine};

double nice_step(double range) {
  const double raw = range / 5.0;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (raw <= m * base) return m * base;
  return 10 * base;
}

// Axes with a y scale from 0 to `top`; returns the plot rectangle.
QRectF axes(QPainter& p, const QRectF& area, const QString& title, const QString& y_label,
            double top, double* y_max) {
  const QFontMetricsF fm(p.font());
  const QRectF plot(area.left() + fm.height() * 1.4 + fm.horizontalAdvance("000.0"),
                    area.top() + fm.height() * 1.8, 0, 0);
  QRectF r = plot;
  r.setRight(area.right() - 8);
  r.setBottom(area.bottom() - fm.height() * 3.0);
  p.setPen(Qt::black);
  QFont bold = p.font();
  bold.setBold(true);
  p.save();
  p.setFont(bold);
  p.drawText(QRectF(area.left(), area.top(), area.width(), fm.height() * 1.5),
             Qt::AlignHCenter | Qt::AlignVCenter, title);
  p.restore();
  const double step = nice_step(std::max(top, 1e-9));
  *y_max = std::ceil(top / step) * step;
  for (double v = 0; v <= *y_max + 1e-9; v += step) {
    const double y = r.bottom() - v / *y_max * r.height();
    p.setPen(QPen(QColor(225, 225, 225), 0));
    p.drawLine(QPointF(r.left(), y), QPointF(r.right(), y));
    p.setPen(Qt::black);
    p.drawText(QRectF(area.left(), y - fm.height() / 2, r.left() - area.left() - 4, fm.height()),
               Qt::AlignRight | Qt::AlignVCenter, QString::number(v, 'g', 4));
  }
  p.setPen(QPen(Qt::black, 1));
  p.drawLine(r.bottomLeft(), r.topLeft());
  p.drawLine(r.bottomLeft(), r.bottomRight());
  p.save();
  p.translate(area.left() + fm.height() * 0.2, r.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-r.height() / 2, 0, r.height(), fm.height()), Qt::AlignCenter, y_label);
  p.restore();
  return r;
}

void error_bar(QPainter& p, double x, double y_low, double y_high, double half_width) {
  p.setPen(QPen(Qt::black, 1.2));
  p.drawLine(QPointF(x, y_low), QPointF(x, y_high));
  p.drawLine(QPointF(x - half_width, y_low), QPointF(x + half_width, y_low));
  p.drawLine(QPointF(x - half_width, y_high), QPointF(x + half_width, y_high));
}

QString join(const std::vector<std::string>& levels, std::size_t from = 0) {
  QStringList parts;
  for (std::size_t k = from; k < levels.size(); ++k) parts << QString::fromStdString(levels[k]);
  return parts.join(" ");
}

}  // namespace

void paint_time_by_condition(QPainter& p, const QRectF& area,
                             const std::vector<studies::CellSummary>& cells) {
  double top = 0;
  for (const auto& c : cells) top = std::max(top, c.mean + c.se);
  double y_max = 1;
  const QRectF r = axes(p, area, QObject::tr("Completion time per condition (mean ± SE)"),
                        QObject::tr("Completion time (s)"), top * 1.1, &y_max);
  if (cells.empty()) return;
  const double slot = r.width() / double(cells.size());
  const QFontMetricsF fm(p.font());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto& c = cells[k];
    const double x0 = r.left() + slot * (double(k) + 0.2), w = slot * 0.6;
    const double y = r.bottom() - c.mean / y_max * r.height();
    const int style = int(k % 4);
    p.setPen(QPen(Qt::black, 1));
    p.setBrush(QBrush(kShades[style], kPatterns[style]));
    p.drawRect(QRectF(x0, y, w, r.bottom() - y));
    error_bar(p, x0 + w / 2, r.bottom() - (c.mean - c.se) / y_max * r.height(),
              r.bottom() - (c.mean + c.se) / y_max * r.height(), w * 0.15);
    p.setPen(Qt::black);
    p.drawText(QRectF(r.left() + slot * double(k), r.bottom() + 2, slot, fm.height() * 2.4),
               Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap,
               join(c.levels) + QString("\nn = %1").arg(c.n));
  }
}

void paint_time_by_repetition(QPainter& p, const QRectF& area, const QString& factor,
                              const std::vector<studies::CellSummary>& cells) {
  std::vector<std::string> levels, reps;
  double top = 0;
  for (const auto& c : cells) {
    if (std::find(levels.begin(), levels.end(), c.levels[0]) == levels.end())
      levels.push_back(c.levels[0]);
    if (std::find(reps.begin(), reps.end(), c.levels[1]) == reps.end()) reps.push_back(c.levels[1]);
    top = std::max(top, c.mean + c.se);
  }
  std::sort(reps.begin(), reps.end(),
            [](const std::string& a, const std::string& b) { return std::stod(a) < std::stod(b); });
  double y_max = 1;
  const QRectF r = axes(p, area, QObject::tr("Completion time per repetition by %1").arg(factor),
                        QObject::tr("Completion time (s)"), top * 1.15, &y_max);
  if (reps.empty()) return;
  const QFontMetricsF fm(p.font());
  auto x_of = [&](const std::string& rep) {
    const auto k = double(std::find(reps.begin(), reps.end(), rep) - reps.begin());
    return r.left() + r.width() * (k + 0.5) / double(reps.size());
  };
  for (const std::string& rep : reps)
    p.drawText(QRectF(x_of(rep) - 30, r.bottom() + 2, 60, fm.height()), Qt::AlignCenter,
               QString::fromStdString(rep));
  p.drawText(QRectF(r.left(), r.bottom() + fm.height() + 2, r.width(), fm.height()),
             Qt::AlignCenter, QObject::tr("Repetition"));
  for (std::size_t l = 0; l < levels.size(); ++l) {
    QPainterPath line;
    const double offset = (double(l) - 0.5 * double(levels.size() - 1)) * 4.0;
    for (const auto& c : cells) {
      if (c.levels[0] != levels[l]) continue;
      const QPointF point(x_of(c.levels[1]) + offset, r.bottom() - c.mean / y_max * r.height());
      if (line.elementCount() == 0)
        line.moveTo(point);
      else
        line.lineTo(point);
      error_bar(p, point.x(), r.bottom() - (c.mean - c.se) / y_max * r.height(),
                r.bottom() - (c.mean + c.se) / y_max * r.height(), 3);
    }
    p.setPen(QPen(kShades[l % 4], 2, kLines[l % 4]));
    p.setBrush(Qt::NoBrush);
    p.drawPath(line);
    for (int e = 0; e < line.elementCount(); ++e) {
      p.setBrush(l % 2 ? Qt::white : Qt::black);
      p.setPen(QPen(Qt::black, 1));
      p.drawEllipse(QPointF(line.elementAt(e).x, line.elementAt(e).y), 3.5, 3.5);
    }
    // Legend.
    const double ly = r.top() + 6 + double(l) * fm.height() * 1.2;
    p.setPen(QPen(kShades[l % 4], 2, kLines[l % 4]));
    p.drawLine(QPointF(r.right() - 120, ly + fm.height() / 2),
               QPointF(r.right() - 90, ly + fm.height() / 2));
    p.setPen(Qt::black);
    p.drawText(QRectF(r.right() - 85, ly, 85, fm.height()), Qt::AlignLeft | Qt::AlignVCenter,
               QString::fromStdString(levels[l]));
  }
}

void paint_items(
    QPainter& p, const QRectF& area,
    const std::vector<std::pair<std::string, std::vector<studies::CellSummary>>>& items,
    int scale_points) {
  if (items.empty()) return;
  const double panel_width = area.width() / double(items.size());
  const QFontMetricsF fm(p.font());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const QRectF panel(area.left() + panel_width * double(i), area.top(), panel_width,
                       area.height());
    double y_max = 1;
    const QRectF r =
        axes(p, panel, QString::fromStdString(items[i].first) + QObject::tr(" (median, range)"),
             QObject::tr("Answer (1–%1)").arg(scale_points), scale_points, &y_max);
    const auto& cells = items[i].second;
    const double slot = r.width() / double(std::max<std::size_t>(1, cells.size()));
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const auto& c = cells[k];
      const double x = r.left() + slot * (double(k) + 0.5);
      auto y = [&](double v) { return r.bottom() - v / y_max * r.height(); };
      error_bar(p, x, y(c.min), y(c.max), slot * 0.12);
      p.setBrush(QBrush(kShades[k % 4], kPatterns[k % 4]));
      p.setPen(QPen(Qt::black, 1));
      p.drawRect(QRectF(x - slot * 0.18, y(c.median) - 3, slot * 0.36, 6));
      p.drawText(QRectF(r.left() + slot * double(k), r.bottom() + 2, slot, fm.height() * 2.4),
                 Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap, join(c.levels));
    }
  }
}

}  // namespace handlab::gui
