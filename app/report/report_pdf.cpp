#include "app/report/report_pdf.h"

#include <algorithm>
#include <stdexcept>

#include <QBuffer>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>

#include "app/report/report_figures.h"
#include "core/util/output_file.h"

namespace handlab::report {
namespace {

// Everything in points (1/72 in): the writer's resolution is 72 dpi, which costs nothing in a
// PDF (text and figures are vectors) and makes a font's point size its size on the page.
constexpr double kPageWidth = 595.28, kPageHeight = 841.89, kMargin = 56.0;
constexpr double kFooter = 28.0;
constexpr double kBodyWidth = kPageWidth - 2 * kMargin;
constexpr double kBottom = kPageHeight - kMargin - kFooter;
constexpr double kCellPadding = 4.0;

QFont font(double size, bool bold = false, bool italic = false,
           const char* family = "DejaVu Serif") {
  QFont f(family);
  f.setPointSizeF(size);
  f.setBold(bold);
  f.setItalic(italic);
  return f;
}

// A line as the PDF sets it: no line break inside "p < .001" or before a number.
QString line_text(const studies::ReportLine& line) {
  QString out;
  for (const studies::ReportText& t : line) {
    QString part = QString::fromStdString(t.text);
    if (!t.source.empty()) {
      part.replace(QChar('.'), QString(QChar('.')) + QChar(0x2060));  // word joiner
      if (out.endsWith(' ')) out[out.size() - 1] = QChar(0x00A0);
      // "p = .008", "F(1, 19) = 8.78": the relation stays with its number.
      if (out.size() >= 3 && out[out.size() - 3] == ' ' &&
          QString("=<>").contains(out[out.size() - 2]))
        out[out.size() - 3] = QChar(0x00A0);
    }
    out += part;
  }
  return out;
}

class PdfLayout {
 public:
  PdfLayout(QPainter& p, QPdfWriter* writer, const studies::ReportDocument& doc,
            const studies::StudyDatabaseAnalysis& a, int pages)
      : p_(p), writer_(writer), doc_(doc), a_(a), pages_(pages) {}

  int run() {
    page_ = 1;
    y_ = kMargin;
    text(QString::fromStdString(doc_.title), font(18, true), 6);
    text(QString::fromStdString(doc_.subtitle), font(10, false, true), 14);
    for (const studies::ReportBlock& b : doc_.blocks) {
      switch (b.kind) {
        case studies::ReportBlock::Kind::kHeading: {
          const QFont f = font(b.level == 1 ? 13.5 : 11.5, true);
          // A heading stays with what follows it.
          if (y_ + height(QString::fromStdString(studies::plain(b.text)), f) + 80 > kBottom)
            new_page();
          y_ += b.level == 1 ? 10 : 4;
          text(QString::fromStdString(studies::plain(b.text)), f, 5);
          if (b.level == 1 && drawing()) {
            p_.setPen(QPen(Qt::gray, 0.5));
            p_.drawLine(QPointF(kMargin, y_ - 3), QPointF(kMargin + kBodyWidth, y_ - 3));
          }
          break;
        }
        case studies::ReportBlock::Kind::kParagraph:
          text(line_text(b.text), font(10), 7);
          break;
        case studies::ReportBlock::Kind::kTable:
          table(b.table);
          break;
        case studies::ReportBlock::Kind::kFigure:
          figure(b.figure);
          break;
      }
    }
    footer();
    return page_;
  }

 private:
  bool drawing() const { return writer_ != nullptr; }

  double height(const QString& s, const QFont& f, double width = kBodyWidth) {
    p_.setFont(f);
    return p_.boundingRect(QRectF(0, 0, width, 1e6), Qt::TextWordWrap, s).height();
  }

  void new_page() {
    footer();
    if (drawing()) writer_->newPage();
    ++page_;
    y_ = kMargin;
  }

  void footer() {
    if (!drawing()) return;
    p_.setFont(font(8.5, false, false, "DejaVu Sans"));
    p_.setPen(Qt::darkGray);
    p_.drawText(QRectF(kMargin, kPageHeight - kMargin, kBodyWidth, 14),
                Qt::AlignRight | Qt::AlignVCenter, QString("%1 / %2").arg(page_).arg(pages_));
    p_.drawText(QRectF(kMargin, kPageHeight - kMargin, kBodyWidth, 14),
                Qt::AlignLeft | Qt::AlignVCenter, QString::fromStdString(doc_.title).left(80));
  }

  void text(const QString& s, const QFont& f, double after) {
    const double h = height(s, f);
    if (y_ + h > kBottom) new_page();
    if (drawing()) {
      p_.setFont(f);
      p_.setPen(Qt::black);
      p_.drawText(QRectF(kMargin, y_, kBodyWidth, h), Qt::TextWordWrap, s);
    }
    y_ += h + after;
  }

  void table(const studies::ReportTable& t) {
    const QFont body = font(8.5, false, false, "DejaVu Sans");
    const QFont bold = font(8.5, true, false, "DejaVu Sans");
    const std::size_t columns = t.header.size();
    std::vector<QString> header(columns);
    std::vector<std::vector<QString>> cells;
    for (std::size_t c = 0; c < columns; ++c) header[c] = QString::fromStdString(t.header[c]);
    for (const auto& row : t.rows) {
      std::vector<QString> r(columns);
      for (std::size_t c = 0; c < columns && c < row.size(); ++c) r[c] = line_text(row[c]);
      cells.push_back(r);
    }
    // Natural widths; the first column (labels) wraps to whatever the others leave.
    std::vector<double> width(columns, 0.0);
    for (std::size_t c = 0; c < columns; ++c) {
      p_.setFont(bold);
      width[c] = p_.boundingRect(QRectF(0, 0, 1e6, 1e6), 0, header[c]).width();
      p_.setFont(body);
      for (const auto& r : cells)
        width[c] = std::max(width[c], p_.boundingRect(QRectF(0, 0, 1e6, 1e6), 0, r[c]).width());
      width[c] += 2 * kCellPadding;
    }
    double others = 0;
    for (std::size_t c = 1; c < columns; ++c) others += width[c];
    if (others + width[0] > kBodyWidth) {
      // Shrink the widest columns in turn until the table fits.
      while (true) {
        double total = 0;
        for (double w : width) total += w;
        if (total <= kBodyWidth) break;
        auto widest = std::max_element(width.begin(), width.end());
        *widest -= std::min(*widest * 0.1, total - kBodyWidth) + 0.5;
      }
    }
    auto row_height = [&](const std::vector<QString>& r, const QFont& f) {
      double h = 0;
      for (std::size_t c = 0; c < columns; ++c)
        h = std::max(h, height(r[c], f, width[c] - 2 * kCellPadding));
      return h + 2 * 2.0;
    };
    auto draw_row = [&](const std::vector<QString>& r, const QFont& f, double h) {
      if (!drawing()) return;
      p_.setFont(f);
      p_.setPen(Qt::black);
      double x = kMargin;
      for (std::size_t c = 0; c < columns; ++c) {
        const Qt::Alignment align = t.numeric(c) ? Qt::AlignRight : Qt::AlignLeft;
        p_.drawText(QRectF(x + kCellPadding, y_ + 2, width[c] - 2 * kCellPadding, h - 4),
                    int(align | Qt::AlignTop) | Qt::TextWordWrap, r[c]);
        x += width[c];
      }
    };
    double table_width = 0;
    for (double w : width) table_width += w;
    auto rule = [&](double thickness) {
      if (drawing()) {
        p_.setPen(QPen(Qt::black, thickness));
        p_.drawLine(QPointF(kMargin, y_), QPointF(kMargin + table_width, y_));
      }
    };
    const QFont caption = font(9.5, false, true);
    const QString caption_text = QString::fromStdString(t.caption);
    const double header_h = row_height(header, bold);
    const double first_row = cells.empty() ? 0 : row_height(cells.front(), body);
    if (y_ + height(caption_text, caption) + header_h + first_row + 10 > kBottom) new_page();
    text(caption_text, caption, 3);
    auto head = [&] {
      rule(1.0);
      draw_row(header, bold, header_h);
      y_ += header_h;
      rule(0.5);
    };
    head();
    for (const auto& r : cells) {
      const double h = row_height(r, body);
      if (y_ + h > kBottom) {
        rule(1.0);
        new_page();
        text(caption_text + " (continued)", caption, 3);
        head();
      }
      draw_row(r, body, h);
      y_ += h;
    }
    rule(1.0);
    y_ += 4;
    if (!t.note.empty()) text("Note. " + QString::fromStdString(t.note), font(8.5, false, true), 0);
    y_ += 8;
  }

  void figure(const studies::ReportFigure& f) {
    const double h = figure_height(f.kind, a_, kBodyWidth);
    const QFont caption = font(9, false, true);
    const QString caption_text = QString::fromStdString(f.caption);
    const double total = h + 4 + height(caption_text, caption);
    if (y_ + total > kBottom) new_page();
    if (drawing()) {
      p_.save();
      QFont small("DejaVu Sans");
      small.setPointSizeF(8);
      p_.setFont(small);
      paint_figure(p_, QRectF(kMargin, y_, kBodyWidth, h), f, a_, doc_);
      p_.restore();
    }
    y_ += h + 4;
    text(caption_text, caption, 12);
  }

  QPainter& p_;
  QPdfWriter* writer_;
  const studies::ReportDocument& doc_;
  const studies::StudyDatabaseAnalysis& a_;
  int pages_ = 0, page_ = 1;
  double y_ = kMargin;
};

}  // namespace

int write_report_pdf(const studies::ReportDocument& doc, const studies::StudyDatabaseAnalysis& a,
                     const QString& path) {
  // Drawn into memory, then written by the one output rule (a temporary file renamed over
  // the output, or through a device or pipe).
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  int pages = 0;
  {
    QPdfWriter writer(&buffer);
    writer.setPageSize(QPageSize(QPageSize::A4));
    writer.setPageMargins(QMarginsF(0, 0, 0, 0));
    writer.setResolution(72);
    writer.setTitle(QString::fromStdString(doc.title));
    writer.setCreator("handlab");
    QPainter p;
    if (!p.begin(&writer)) throw util::OutputError("cannot write " + path.toStdString());
    // The first pass only measures, to know the page count for the footers.
    pages = PdfLayout(p, nullptr, doc, a, 0).run();
    PdfLayout(p, &writer, doc, a, pages).run();
    p.end();
  }
  util::write_output_bytes(path.toStdString(),
                           std::string_view(bytes.constData(), std::size_t(bytes.size())));
  return pages;
}

}  // namespace handlab::report
