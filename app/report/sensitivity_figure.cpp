#include "app/report/sensitivity_figure.h"

#include "app/report/figure_file.h"
#include "app/report/figure_labels.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <QFont>
#include <QFontMetricsF>
#include <QPainter>

namespace handlab::report {
namespace {

constexpr int kNamed = 5;  // parameters labelled per panel, by mu*

double finite_or_zero(double v) {
  return std::isfinite(v) ? v : 0.0;
}

// A round upper bound for an axis: 1, 2 or 5 times a power of ten.
double axis_top(double v) {
  if (!(v > 0)) return 1.0;
  const double scale = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * scale >= v) return m * scale;
  return 10.0 * scale;
}

void panel(QPainter& p, const QRectF& area, const studies::SensitivityReport& r, std::size_t o,
           double em) {
  const auto& m = r.indices[o];
  double top_x = 0, top_y = 0;
  for (const studies::MorrisIndex& i : m) {
    top_x = std::max(top_x, finite_or_zero(i.mu_star));
    top_y = std::max(top_y, finite_or_zero(i.sigma));
  }
  top_x = axis_top(top_x);
  top_y = axis_top(top_y);
  const QRectF plot(area.left() + 4 * em, area.top() + 2.4 * em, area.width() - 5 * em,
                    area.height() - 5.4 * em);
  auto x = [&](double v) { return plot.left() + v / top_x * plot.width(); };
  auto y = [&](double v) { return plot.bottom() - v / top_y * plot.height(); };
  p.setPen(Qt::black);
  p.drawText(QRectF(area.left(), area.top() + 0.3 * em, area.width(), 1.8 * em), Qt::AlignHCenter,
             QString::fromStdString(r.outputs[o]));
  p.setPen(QPen(QColor(225, 225, 225), 0.6));
  for (int k = 1; k <= 4; ++k) {
    p.drawLine(QPointF(plot.left(), y(top_y * k / 4)), QPointF(plot.right(), y(top_y * k / 4)));
    p.drawLine(QPointF(x(top_x * k / 4), plot.top()), QPointF(x(top_x * k / 4), plot.bottom()));
  }
  // sigma = mu*: above it the effect is mostly interaction or non-linearity.
  p.setPen(QPen(QColor(150, 150, 150), 1.0, Qt::DashLine));
  const double diagonal = std::min(top_x, top_y);
  p.drawLine(QPointF(x(0), y(0)), QPointF(x(diagonal), y(diagonal)));
  p.setPen(QPen(Qt::black, 1.0));
  p.drawLine(plot.bottomLeft(), plot.topLeft());
  p.drawLine(plot.bottomLeft(), plot.bottomRight());
  for (int k = 0; k <= 4; ++k) {
    p.drawText(QRectF(x(top_x * k / 4) - 2.5 * em, plot.bottom() + 0.3 * em, 5 * em, 1.4 * em),
               Qt::AlignHCenter, QString::number(top_x * k / 4, 'g', 3));
    p.drawText(QRectF(plot.left() - 3.8 * em, y(top_y * k / 4) - 0.7 * em, 3.4 * em, 1.4 * em),
               Qt::AlignRight | Qt::AlignVCenter, QString::number(top_y * k / 4, 'g', 3));
  }
  p.drawText(QRectF(plot.left(), plot.bottom() + 1.7 * em, plot.width(), 1.4 * em),
             Qt::AlignHCenter, "μ*: mean |elementary effect|");
  p.save();
  p.translate(area.left() + 0.9 * em, plot.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-plot.height() / 2, -0.8 * em, plot.height(), 1.6 * em), Qt::AlignHCenter,
             "σ: SD of the elementary effects");
  p.restore();
  std::vector<std::size_t> order(m.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return finite_or_zero(m[a].mu_star) > finite_or_zero(m[b].mu_star);
  });
  // Labels stay right of the y axis, clear of its numbers and title.
  const QRectF labels(plot.left(), plot.top(), area.right() - plot.left(), plot.height());
  std::vector<QRectF> taken;  // the named points' markers and the labels placed so far
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    const studies::MorrisIndex& i = m[order[rank]];
    if (!std::isfinite(i.mu_star)) continue;
    const QPointF at(x(i.mu_star), y(finite_or_zero(i.sigma)));
    const bool named = int(rank) < kNamed;
    p.setPen(QPen(named ? QColor(0, 90, 181) : QColor(120, 120, 120), 1.0));
    p.setBrush(named ? QBrush(QColor(0, 90, 181)) : QBrush(Qt::white));
    p.drawEllipse(at, 0.28 * em, 0.28 * em);
    if (named) taken.emplace_back(at.x() - 0.3 * em, at.y() - 0.3 * em, 0.6 * em, 0.6 * em);
  }
  for (int rank = 0; rank < std::min<int>(kNamed, int(order.size())); ++rank) {
    const studies::MorrisIndex& i = m[order[std::size_t(rank)]];
    if (!std::isfinite(i.mu_star)) continue;
    const QPointF at(x(i.mu_star), y(finite_or_zero(i.sigma)));
    const QString name = QString::fromStdString(r.parameters[order[std::size_t(rank)]].name);
    const QRectF label = place_label(
        at, QFontMetricsF(p.font(), p.device()).horizontalAdvance(name), em, labels, taken);
    // A label moved off its point's height is tied to it by a line.
    if (std::abs(label.center().y() - at.y()) > 0.1 * em) {
      const bool right = label.center().x() > at.x();
      p.setPen(QPen(QColor(120, 120, 120), 0.8));
      p.drawLine(at, QPointF(right ? label.left() : label.right(), label.center().y()));
    }
    p.setPen(Qt::black);
    p.drawText(label, Qt::AlignCenter, name);
  }
}

void paint(QPainter& p, const QRectF& area, const studies::SensitivityReport& r,
           const std::string& title) {
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(area, Qt::white);
  QFont font("DejaVu Sans");
  font.setPixelSize(int(area.height() / 30));
  p.setFont(font);
  const double em = font.pixelSize();
  p.setPen(Qt::black);
  p.drawText(QRectF(area.left(), area.top() + 0.3 * em, area.width(), 1.8 * em), Qt::AlignHCenter,
             QString::fromStdString(title));
  const double width = area.width() / double(std::max<std::size_t>(1, r.outputs.size()));
  for (std::size_t o = 0; o < r.outputs.size(); ++o)
    panel(
        p,
        QRectF(area.left() + double(o) * width, area.top() + 2 * em, width, area.height() - 2 * em),
        r, o, em);
}

}  // namespace

void write_sensitivity_figure(const studies::SensitivityReport& report, const std::string& title,
                              const std::string& path) {
  write_figure_file(path, QSize(int(560 * std::max<std::size_t>(1, report.outputs.size())), 560),
                    title, [&](QPainter& p, const QRectF& area) { paint(p, area, report, title); });
}

}  // namespace handlab::report
