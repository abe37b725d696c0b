#include "app/report/power_figure.h"

#include "app/report/figure_file.h"
#include "app/report/figure_marker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <QFont>
#include <QPainter>
#include <QPainterPath>

namespace handlab::report {
namespace {

const power::PowerEstimate& named(const power::PowerReport& r, const std::string& name) {
  for (const auto* list : {&r.effects, &r.contrasts})
    for (const power::PowerEstimate& e : *list)
      if (e.name == name) return e;
  throw std::runtime_error("the power report has no effect or contrast named '" + name + "'");
}

// Greyscale-readable: each curve its own dash pattern and marker as well as shade.
const Qt::PenStyle kStyles[] = {Qt::SolidLine, Qt::DashLine, Qt::DotLine, Qt::DashDotLine,
                                Qt::DashDotDotLine};
const QColor kColours[] = {QColor(20, 20, 20), QColor(0, 90, 181), QColor(220, 50, 32),
                           QColor(0, 140, 70), QColor(120, 60, 160)};

void paint(QPainter& p, const QRectF& area, const power::PowerReport& r,
           const std::vector<std::string>& names, double target, const std::string& title) {
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(area, Qt::white);
  QFont font("DejaVu Sans");
  font.setPixelSize(int(area.height() / 34));
  p.setFont(font);
  const double em = font.pixelSize();
  const double legend_h = (double(names.size()) + 0.5) * 1.5 * em;
  const QRectF plot(area.left() + 4.5 * em, area.top() + 2.5 * em, area.width() - 6 * em,
                    area.height() - 6.5 * em - legend_h);
  const double n0 = r.n.front(), n1 = std::max<double>(r.n.back(), n0 + 1);
  auto x = [&](double n) { return plot.left() + (n - n0) / (n1 - n0) * plot.width(); };
  auto y = [&](double power) { return plot.bottom() - power * plot.height(); };
  p.setPen(Qt::black);
  p.drawText(QRectF(area.left(), area.top() + 0.4 * em, area.width(), 1.8 * em), Qt::AlignHCenter,
             QString::fromStdString(title));
  // Axes, grid and ticks.
  p.setPen(QPen(QColor(225, 225, 225), 0.6));
  for (int k = 0; k <= 10; k += 2)
    p.drawLine(QPointF(plot.left(), y(k / 10.0)), QPointF(plot.right(), y(k / 10.0)));
  p.setPen(QPen(Qt::black, 1.0));
  p.drawLine(plot.bottomLeft(), plot.topLeft());
  p.drawLine(plot.bottomLeft(), plot.bottomRight());
  for (int k = 0; k <= 10; k += 2) {
    p.drawLine(QPointF(plot.left() - 0.3 * em, y(k / 10.0)), QPointF(plot.left(), y(k / 10.0)));
    p.drawText(QRectF(plot.left() - 3.2 * em, y(k / 10.0) - 0.7 * em, 2.7 * em, 1.4 * em),
               Qt::AlignRight | Qt::AlignVCenter, QString::number(k / 10.0, 'f', 1));
  }
  const int step = std::max(1, int(r.n.size() / 8));
  for (std::size_t k = 0; k < r.n.size(); k += std::size_t(step)) {
    p.drawLine(QPointF(x(r.n[k]), plot.bottom()), QPointF(x(r.n[k]), plot.bottom() + 0.3 * em));
    p.drawText(QRectF(x(r.n[k]) - 2 * em, plot.bottom() + 0.4 * em, 4 * em, 1.4 * em),
               Qt::AlignHCenter, QString::number(r.n[k]));
  }
  p.drawText(QRectF(plot.left(), plot.bottom() + 1.8 * em, plot.width(), 1.4 * em),
             Qt::AlignHCenter, "participants (N)");
  p.save();
  p.translate(area.left() + 1.0 * em, plot.center().y());
  p.rotate(-90);
  p.drawText(
      QRectF(-plot.height() / 2, -0.8 * em, plot.height(), 1.6 * em), Qt::AlignHCenter,
      r.sims ? QString("power (%1 simulations per N)").arg(r.sims) : QString("power (exact)"));
  p.restore();
  // The target.
  p.setPen(QPen(QColor(110, 110, 110), 1.0, Qt::DashLine));
  p.drawLine(QPointF(plot.left(), y(target)), QPointF(plot.right(), y(target)));
  p.drawText(QRectF(plot.right() - 6 * em, y(target) - 1.5 * em, 6 * em, 1.4 * em), Qt::AlignRight,
             QString("target %1").arg(target, 0, 'f', 2));
  // The curves, each point with its 95 % interval.
  for (std::size_t i = 0; i < names.size(); ++i) {
    const power::PowerEstimate& e = named(r, names[i]);
    const QColor colour = kColours[i % 5];
    QPainterPath path;
    for (std::size_t k = 0; k < r.n.size(); ++k) {
      const QPointF at(x(r.n[k]), y(e.power[k]));
      k == 0 ? path.moveTo(at) : path.lineTo(at);
    }
    p.setBrush(Qt::NoBrush);
    p.setPen(QPen(colour, 1.6, kStyles[i % 5]));
    p.drawPath(path);
    p.setPen(QPen(colour, 1.0));
    for (std::size_t k = 0; k < r.n.size(); ++k) {
      if (e.upper[k] > e.lower[k])
        p.drawLine(QPointF(x(r.n[k]), y(e.lower[k])), QPointF(x(r.n[k]), y(e.upper[k])));
      p.setBrush(i % 2 ? QBrush(Qt::white) : QBrush(colour));
      draw_marker(p, int(i), QPointF(x(r.n[k]), y(e.power[k])), 0.28 * em);
    }
    // Legend.
    const double ly = plot.bottom() + 3.8 * em + double(i) * 1.5 * em;
    p.setPen(QPen(colour, 1.6, kStyles[i % 5]));
    p.drawLine(QPointF(plot.left(), ly), QPointF(plot.left() + 3 * em, ly));
    p.setPen(QPen(colour, 1.0));
    draw_marker(p, int(i), QPointF(plot.left() + 1.5 * em, ly), 0.28 * em);
    p.setPen(Qt::black);
    p.drawText(QRectF(plot.left() + 3.6 * em, ly - 0.75 * em, plot.width() - 3.6 * em, 1.5 * em),
               Qt::AlignVCenter | Qt::AlignLeft, QString::fromStdString(names[i]));
  }
}

}  // namespace

void write_power_figure(const power::PowerReport& report, const std::vector<std::string>& names,
                        double target, const std::string& title, const std::string& path) {
  for (const std::string& n : names) named(report, n);  // every name known before a file is made
  write_figure_file(
      path, QSize(900, int(560 + 27 * names.size())), title,
      [&](QPainter& p, const QRectF& area) { paint(p, area, report, names, target, title); });
}

}  // namespace handlab::report
