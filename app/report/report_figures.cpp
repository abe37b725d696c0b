#include "app/report/report_figures.h"

#include "app/report/figure_marker.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <QBuffer>
#include <QObject>
#include <QPainter>
#include <QPainterPath>
#include <QSvgGenerator>

namespace handlab::report {
namespace {

constexpr int kCellLabelFlags = Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap;
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

// A level's marker, the same in every figure: filled circle, open square, filled triangle,
// open diamond, then again.
void marker(QPainter& p, const QPointF& at, std::size_t level) {
  p.setPen(QPen(Qt::black, 1));
  p.setBrush(level % 2 ? Qt::white : Qt::black);
  draw_marker(p, int(level), at, 3.5);
}

// Level `level`'s line, marker and name in the top right corner of the plot `r`.
void legend_entry(QPainter& p, const QRectF& r, std::size_t level, const QString& name) {
  const QFontMetricsF fm(p.font());
  const double y = r.top() + 4 + double(level) * fm.height() * 1.2 + fm.height() / 2;
  const double x = r.right() - fm.horizontalAdvance("MMMMMMMMMM");
  p.setPen(QPen(kShades[level % 4], 2, kLines[level % 4]));
  p.drawLine(QPointF(x, y), QPointF(x + 24, y));
  marker(p, QPointF(x + 12, y), level);
  p.drawText(QRectF(x + 30, y - fm.height() / 2, r.right() - x - 30, fm.height()),
             Qt::AlignLeft | Qt::AlignVCenter, name);
}

void error_bar(QPainter& p, double x, double y_low, double y_high, double half_width) {
  p.setPen(QPen(Qt::black, 1.2));
  p.drawLine(QPointF(x, y_low), QPointF(x, y_high));
  p.drawLine(QPointF(x - half_width, y_low), QPointF(x + half_width, y_low));
  p.drawLine(QPointF(x - half_width, y_high), QPointF(x + half_width, y_high));
}

QString display(const std::string& name) {
  QString s = QString::fromStdString(name).replace('_', ' ');
  if (!s.isEmpty()) s[0] = s[0].toUpper();
  return s;
}

QString join(const std::vector<std::string>& levels) {
  QStringList parts;
  for (const std::string& l : levels) parts << display(l);
  return parts.join(" ");
}

// The font for the cells' names under a figure's bars or boxes: the axes' font, or smaller
// where a design of many cells leaves a slot too narrow for it (the words wrap, and the lines
// must fit under the axis). One size for every name of the figure.
QFont cell_label_font(const QFont& axes_font, const QSizeF& slot, const QStringList& names) {
  QFont font = axes_font;
  for (int smaller = 0; smaller < 4; ++smaller) {
    const QFontMetricsF fm(font);
    const bool fits = std::all_of(names.begin(), names.end(), [&](const QString& name) {
      const QRectF needed = fm.boundingRect(QRectF(QPointF(0, 0), slot), kCellLabelFlags, name);
      return needed.width() <= slot.width() + 0.5 && needed.height() <= slot.height();
    });
    if (fits) break;
    // The PDF's and the app's fonts are sized in points, the SVG's in pixels.
    if (font.pixelSize() > 0)
      font.setPixelSize(std::max(6, int(font.pixelSize() * 0.85)));
    else
      font.setPointSizeF(std::max(4.5, font.pointSizeF() * 0.85));
  }
  return font;
}

// The cells' names under the axis of a plot `r` with one slot a cell.
void cell_labels(QPainter& p, const QRectF& r, const QStringList& names) {
  const double slot = r.width() / double(std::max<qsizetype>(1, names.size()));
  const QSizeF label(slot, QFontMetricsF(p.font()).height() * 3.0 - 2);
  p.save();
  p.setPen(Qt::black);
  p.setFont(cell_label_font(p.font(), label, names));
  for (qsizetype k = 0; k < names.size(); ++k)
    p.drawText(QRectF(QPointF(r.left() + slot * double(k), r.bottom() + 2), label), kCellLabelFlags,
               names[k]);
  p.restore();
}

double error_of(const studies::CellSummary& c, const studies::ReportDocument& doc) {
  return doc.options.error_bars == studies::ErrorBars::kWithinParticipant ? c.se_within : c.se;
}

QString stars(double p) {
  return p < 0.001 ? "***" : p < 0.01 ? "**" : p < 0.05 ? "*" : "n.s.";
}

// Fig. 3.5: bars with error bars, brackets over the planned comparisons.
void time_by_condition(QPainter& p, const QRectF& area, const studies::StudyDatabaseAnalysis& a,
                       const studies::ReportDocument& doc) {
  const auto& cells = a.time_by_condition;
  double top = 0;
  for (const auto& c : cells) top = std::max(top, c.mean + error_of(c, doc));
  // Room for the brackets: one step of 8 % each.
  const double bracket_step = 0.09 * std::max(top, 1e-9);
  const double room = top + bracket_step * double(doc.planned.size() + 1);
  double y_max = 1;
  const QRectF r = axes(p, area, QObject::tr("Completion time per condition"),
                        QObject::tr("Time (s)"), room, &y_max);
  if (cells.empty()) return;
  const double slot = r.width() / double(cells.size());
  const QFontMetricsF fm(p.font());
  auto y_of = [&](double v) { return r.bottom() - v / y_max * r.height(); };
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto& c = cells[k];
    const double x0 = r.left() + slot * (double(k) + 0.2), w = slot * 0.6;
    const int style = int(k % 4);
    p.setPen(QPen(Qt::black, 1));
    p.setBrush(QBrush(kShades[style], kPatterns[style]));
    p.drawRect(QRectF(x0, y_of(c.mean), w, r.bottom() - y_of(c.mean)));
    const double e = error_of(c, doc);
    error_bar(p, x0 + w / 2, y_of(c.mean - e), y_of(c.mean + e), w * 0.15);
  }
  QStringList names;
  for (const auto& c : cells) names << join(c.levels) + QString("\nn = %1").arg(c.n);
  cell_labels(p, r, names);
  // Brackets, the shorter spans lower.
  struct Span {
    std::size_t from, to;
    double p;
  };
  std::vector<Span> spans;
  for (const studies::PlannedComparison& pc : doc.planned) {
    std::size_t i = cells.size(), j = cells.size();
    for (std::size_t k = 0; k < cells.size(); ++k) {
      if (cells[k].levels == pc.first) i = k;
      if (cells[k].levels == pc.second) j = k;
    }
    if (i == cells.size() || j == cells.size()) continue;
    spans.push_back({std::min(i, j), std::max(i, j), pc.p_tukey});
  }
  std::stable_sort(spans.begin(), spans.end(),
                   [](const Span& x, const Span& y) { return x.to - x.from < y.to - y.from; });
  std::vector<double> floor(cells.size(), 0.0);  // the highest drawn over each bar
  for (std::size_t k = 0; k < cells.size(); ++k) floor[k] = cells[k].mean + error_of(cells[k], doc);
  for (const Span& s : spans) {
    double base = 0;
    for (std::size_t k = s.from; k <= s.to; ++k) base = std::max(base, floor[k]);
    const double level = base + bracket_step;
    const double x1 = r.left() + slot * (double(s.from) + 0.5);
    const double x2 = r.left() + slot * (double(s.to) + 0.5);
    const double y = y_of(level), tick = y_of(level - 0.35 * bracket_step);
    p.setPen(QPen(Qt::black, 1));
    p.drawLine(QPointF(x1, tick), QPointF(x1, y));
    p.drawLine(QPointF(x1, y), QPointF(x2, y));
    p.drawLine(QPointF(x2, y), QPointF(x2, tick));
    p.drawText(QRectF(x1, y - fm.height(), x2 - x1, fm.height()),
               Qt::AlignHCenter | Qt::AlignBottom, stars(s.p));
    for (std::size_t k = s.from; k <= s.to; ++k) floor[k] = level + 0.4 * bracket_step;
  }
}

// Fig. 3.6, one panel: mean per repetition, one line per level of the factor.
void time_by_repetition(QPainter& p, const QRectF& area, const std::string& factor,
                        const std::vector<studies::CellSummary>& cells,
                        const studies::ReportDocument& doc) {
  std::vector<std::string> levels, reps;
  double top = 0;
  for (const auto& c : cells) {
    if (std::find(levels.begin(), levels.end(), c.levels[0]) == levels.end())
      levels.push_back(c.levels[0]);
    if (std::find(reps.begin(), reps.end(), c.levels[1]) == reps.end()) reps.push_back(c.levels[1]);
    top = std::max(top, c.mean + error_of(c, doc));
  }
  double y_max = 1;
  const QRectF r = axes(p, area, QObject::tr("By %1").arg(display(factor).toLower()),
                        QObject::tr("Time (s)"), top * 1.25, &y_max);
  if (reps.empty()) return;
  const QFontMetricsF fm(p.font());
  auto x_of = [&](const std::string& rep) {
    const auto k = double(std::find(reps.begin(), reps.end(), rep) - reps.begin());
    return r.left() + r.width() * (k + 0.5) / double(reps.size());
  };
  auto y_of = [&](double v) { return r.bottom() - v / y_max * r.height(); };
  p.setPen(Qt::black);
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
      const QPointF point(x_of(c.levels[1]) + offset, y_of(c.mean));
      if (line.elementCount() == 0)
        line.moveTo(point);
      else
        line.lineTo(point);
      const double e = error_of(c, doc);
      error_bar(p, point.x(), y_of(c.mean - e), y_of(c.mean + e), 3);
    }
    p.setPen(QPen(kShades[l % 4], 2, kLines[l % 4]));
    p.setBrush(Qt::NoBrush);
    p.drawPath(line);
    for (int e = 0; e < line.elementCount(); ++e)
      marker(p, QPointF(line.elementAt(e).x, line.elementAt(e).y), l);
    legend_entry(p, r, l, display(levels[l]));
  }
}

// Fig. 3.7, one panel: each participant's mean per level against hand length, with a
// least-squares line per level.
void time_by_hand_length(QPainter& p, const QRectF& area, const std::string& factor,
                         const std::vector<studies::HandLengthPoint>& points) {
  std::vector<std::string> levels;
  double top = 0, lo = 1e9, hi = -1e9;
  for (const auto& q : points) {
    if (std::find(levels.begin(), levels.end(), q.level) == levels.end()) levels.push_back(q.level);
    top = std::max(top, q.mean);
    lo = std::min(lo, q.hand_length_cm);
    hi = std::max(hi, q.hand_length_cm);
  }
  double y_max = 1;
  const QRectF r = axes(p, area, QObject::tr("By %1").arg(display(factor).toLower()),
                        QObject::tr("Time (s)"), top * 1.2, &y_max);
  if (points.empty()) return;
  const QFontMetricsF fm(p.font());
  if (hi - lo < 1.0) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double step = nice_step(hi - lo);
  const double x_lo = std::floor(lo / step) * step, x_hi = std::ceil(hi / step) * step;
  auto x_of = [&](double v) { return r.left() + (v - x_lo) / (x_hi - x_lo) * r.width(); };
  auto y_of = [&](double v) { return r.bottom() - v / y_max * r.height(); };
  p.setPen(Qt::black);
  for (double v = x_lo; v <= x_hi + 1e-9; v += step)
    p.drawText(QRectF(x_of(v) - 30, r.bottom() + 2, 60, fm.height()), Qt::AlignCenter,
               QString::number(v, 'g', 4));
  p.drawText(QRectF(r.left(), r.bottom() + fm.height() + 2, r.width(), fm.height()),
             Qt::AlignCenter, QObject::tr("Hand length (cm)"));
  for (std::size_t l = 0; l < levels.size(); ++l) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const auto& q : points) {
      if (q.level != levels[l]) continue;
      const QPointF at(x_of(q.hand_length_cm), y_of(q.mean));
      marker(p, at, l);
      sx += q.hand_length_cm;
      sy += q.mean;
      sxx += q.hand_length_cm * q.hand_length_cm;
      sxy += q.hand_length_cm * q.mean;
      ++n;
    }
    const double denominator = n * sxx - sx * sx;
    if (n >= 2 && denominator > 1e-12) {
      const double slope = (n * sxy - sx * sy) / denominator;
      const double intercept = (sy - slope * sx) / n;
      p.setPen(QPen(kShades[l % 4], 2, kLines[l % 4]));
      p.drawLine(QPointF(x_of(x_lo), y_of(intercept + slope * x_lo)),
                 QPointF(x_of(x_hi), y_of(intercept + slope * x_hi)));
    }
    legend_entry(p, r, l, display(levels[l]));
  }
}

// The questionnaire's panels side by side, as in the paper, up to four conditions; one a row
// for more, where side by side would leave a condition too narrow a slot for its name.
bool items_in_rows(const studies::StudyDatabaseAnalysis& a) {
  return !a.items_by_condition.empty() && a.items_by_condition.front().second.size() > 4;
}

// Fig. 3.8: medians with their ranges per condition, one panel per item.
void items(QPainter& p, const QRectF& area, const studies::StudyDatabaseAnalysis& a) {
  const auto& items = a.items_by_condition;
  if (items.empty()) return;
  const int scale_points = a.protocol.scale_points;
  const bool rows = items_in_rows(a);
  const double panel_width = rows ? area.width() : area.width() / double(items.size());
  const double panel_height = rows ? area.height() / double(items.size()) : area.height();
  for (std::size_t i = 0; i < items.size(); ++i) {
    const double at = double(i);
    const QRectF panel(area.left() + (rows ? 0 : panel_width * at),
                       area.top() + (rows ? panel_height * at : 0), panel_width, panel_height);
    double y_max = 1;
    const QRectF r = axes(p, panel, display(items[i].first),
                          QObject::tr("Score (1–%1)").arg(scale_points), scale_points, &y_max);
    const auto& cells = items[i].second;
    const double slot = r.width() / double(std::max<std::size_t>(1, cells.size()));
    auto y = [&](double v) { return r.bottom() - v / y_max * r.height(); };
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const auto& c = cells[k];
      const double x = r.left() + slot * (double(k) + 0.5);
      error_bar(p, x, y(c.min), y(c.max), slot * 0.12);
      p.setBrush(QBrush(kShades[k % 4], kPatterns[k % 4]));
      p.setPen(QPen(Qt::black, 1));
      p.drawRect(QRectF(x - slot * 0.2, y(c.median) - 3.5, slot * 0.4, 7));
    }
    QStringList names;
    for (const auto& c : cells) names << join(c.levels);
    cell_labels(p, r, names);
  }
}

}  // namespace

double figure_height(studies::FigureKind kind, const studies::StudyDatabaseAnalysis& analysis,
                     double width) {
  switch (kind) {
    case studies::FigureKind::kTimeByCondition:
      return 0.55 * width;
    case studies::FigureKind::kItems:
      // In rows, each item's panel 0.3 of the width high, all of them within a page.
      return items_in_rows(analysis)
                 ? std::min(1.2, 0.3 * double(analysis.items_by_condition.size())) * width
                 : 0.42 * width;
    default:
      return 0.45 * width;
  }
}

void paint_figure(QPainter& p, const QRectF& area, const studies::ReportFigure& figure,
                  const studies::StudyDatabaseAnalysis& a, const studies::ReportDocument& doc) {
  p.save();
  p.setRenderHint(QPainter::Antialiasing);
  switch (figure.kind) {
    case studies::FigureKind::kTimeByCondition:
      time_by_condition(p, area, a, doc);
      break;
    case studies::FigureKind::kTimeByRepetition:
    case studies::FigureKind::kTimeByHandLength: {
      const bool repetition = figure.kind == studies::FigureKind::kTimeByRepetition;
      const std::size_t panels =
          repetition ? a.time_by_repetition.size() : a.time_by_hand_length.size();
      const double w = area.width() / double(std::max<std::size_t>(panels, 1));
      for (std::size_t k = 0; k < panels; ++k) {
        const QRectF panel(area.left() + w * double(k), area.top(), w, area.height());
        if (repetition)
          time_by_repetition(p, panel, a.time_by_repetition[k].first,
                             a.time_by_repetition[k].second, doc);
        else
          time_by_hand_length(p, panel, a.time_by_hand_length[k].first,
                              a.time_by_hand_length[k].second);
      }
      break;
    }
    case studies::FigureKind::kItems:
      items(p, area, a);
      break;
  }
  p.restore();
}

std::string figure_svg(const studies::ReportFigure& figure,
                       const studies::StudyDatabaseAnalysis& analysis,
                       const studies::ReportDocument& document, int width) {
  const int height = int(std::ceil(figure_height(figure.kind, analysis, width)));
  QBuffer buffer;
  buffer.open(QIODevice::WriteOnly);
  QSvgGenerator svg;
  svg.setOutputDevice(&buffer);
  svg.setSize(QSize(width, height));
  svg.setViewBox(QRect(0, 0, width, height));
  svg.setResolution(96);
  svg.setTitle(QString::fromStdString(figure.caption));
  {
    QPainter p(&svg);
    QFont font("DejaVu Sans");
    font.setPixelSize(12);
    p.setFont(font);
    p.fillRect(QRectF(0, 0, width, height), Qt::white);
    paint_figure(p, QRectF(0, 0, width, height), figure, analysis, document);
  }
  std::string text = buffer.data().toStdString();
  const std::size_t start = text.find("<svg");
  return start == std::string::npos ? text : text.substr(start);
}

}  // namespace handlab::report
