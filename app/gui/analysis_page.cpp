#include "app/gui/analysis_page.h"

#include <cmath>

#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPushButton>
#include <QScrollArea>
#include <QSplitter>
#include <QTextBrowser>
#include <QTextDocument>
#include <QVBoxLayout>

#include "app/report/report_figures.h"

namespace handlab::gui {

// The report's figures, stacked, painted by the report's figure code (app/report).
class FigurePanel : public QWidget {
 public:
  explicit FigurePanel(QWidget* parent = nullptr) : QWidget(parent) {
    setMinimumSize(520, 400);
    setObjectName("figures");
  }
  void set(const studies::StudyDatabaseAnalysis* a, const studies::ReportDocument* doc) {
    analysis_ = a;
    document_ = doc;
    setMinimumHeight(int(std::ceil(total_height(std::max(width(), 520)))));
    update();
  }

 protected:
  void resizeEvent(QResizeEvent* event) override {
    QWidget::resizeEvent(event);
    setMinimumHeight(int(std::ceil(total_height(width()))));
  }
  void paintEvent(QPaintEvent*) override {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(rect(), Qt::white);
    if (!analysis_ || !document_) {
      p.drawText(rect(), Qt::AlignCenter, tr("Run the analysis to see the figures."));
      return;
    }
    double y = 0;
    const double w = width() - 20;
    for (const studies::ReportBlock& b : document_->blocks) {
      if (b.kind != studies::ReportBlock::Kind::kFigure) continue;
      const double h = report::figure_height(b.figure.kind, *analysis_, w);
      report::paint_figure(p, QRectF(10, y, w, h), b.figure, *analysis_, *document_);
      y += h + kGap;
    }
  }

 private:
  static constexpr double kGap = 16;
  double total_height(int width) const {
    if (!document_ || !analysis_) return 400;
    double h = 0;
    for (const studies::ReportBlock& b : document_->blocks)
      if (b.kind == studies::ReportBlock::Kind::kFigure)
        h += report::figure_height(b.figure.kind, *analysis_, width - 20) + kGap;
    return std::max(h, 400.0);
  }
  const studies::StudyDatabaseAnalysis* analysis_ = nullptr;
  const studies::ReportDocument* document_ = nullptr;
};

namespace {

QString text(const std::string& s) {
  return QString::fromStdString(s);
}

// The report's text and tables (without its figures, which the panel beside them draws) as
// the text browser's HTML.
QString report_html(const studies::ReportDocument& doc) {
  QString html = "<h2>" + text(doc.title).toHtmlEscaped() + "</h2>";
  for (const studies::ReportBlock& b : doc.blocks) {
    switch (b.kind) {
      case studies::ReportBlock::Kind::kHeading:
        html += (b.level == 1 ? "<h3>" : "<h4>") + text(studies::plain(b.text)).toHtmlEscaped() +
                (b.level == 1 ? "</h3>" : "</h4>");
        break;
      case studies::ReportBlock::Kind::kParagraph:
        html += "<p>" + text(studies::plain(b.text)).toHtmlEscaped() + "</p>";
        break;
      case studies::ReportBlock::Kind::kTable:
        html += text(studies::report_table_html(b.table))
                    .replace("<table>", "<table border=1 cellspacing=0 cellpadding=3>");
        break;
      case studies::ReportBlock::Kind::kFigure:
        html += "<p><i>" + text(b.figure.caption).toHtmlEscaped() + " (beside)</i></p>";
        break;
    }
  }
  return html;
}

}  // namespace

AnalysisPage::AnalysisPage(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* bar = new QHBoxLayout;
  run_ = new QPushButton(tr("Run Analysis (Ctrl+Shift+R)"));
  run_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_R));
  status_ = new QLabel;
  status_->setObjectName("analysis_status");
  bar->addWidget(run_);
  bar->addWidget(status_, 1);
  layout->addLayout(bar);
  connect(run_, &QPushButton::clicked, this, &AnalysisPage::run);
  auto* split = new QSplitter;
  tables_ = new QTextBrowser;
  tables_->setObjectName("analysis_tables");
  tables_->document()->setDefaultStyleSheet("td.num, th.num { text-align: right; }");
  split->addWidget(tables_);
  auto* scroll = new QScrollArea;
  figures_ = new FigurePanel;
  scroll->setWidget(figures_);
  scroll->setWidgetResizable(true);
  split->addWidget(scroll);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  split->setSizes({700, 560});
  layout->addWidget(split, 1);
  connect(this, &AnalysisPage::ready, this, &AnalysisPage::show_result);
  connect(this, &AnalysisPage::failed, this, [this](const QString& error) {
    if (worker_.joinable()) worker_.join();
    status_->setText(error);
    run_->setEnabled(true);
  });
  set_study({});
}

AnalysisPage::~AnalysisPage() {
  if (worker_.joinable()) worker_.join();
}

void AnalysisPage::set_study(const QString& database) {
  if (worker_.joinable()) worker_.join();
  database_ = database;
  result_.reset();
  document_.reset();
  figures_->set(nullptr, nullptr);
  tables_->setHtml(database.isEmpty() ? tr("<p>Open a study to analyse it.</p>")
                                      : tr("<p>Run the analysis to see the tables.</p>"));
  run_->setEnabled(!database.isEmpty());
  status_->clear();
}

void AnalysisPage::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (!result_ && !busy() && !database_.isEmpty()) run();
}

void AnalysisPage::run() {
  if (database_.isEmpty() || worker_.joinable()) return;
  run_->setEnabled(false);
  status_->setText(tr("Analysing…"));
  const std::string path = database_.toStdString();
  worker_ = std::thread([this, path] {
    try {
      auto analysis = studies::analyze_study_database(path);
      QMetaObject::invokeMethod(
          this,
          [this, a = std::move(analysis)]() mutable {
            if (worker_.joinable()) worker_.join();
            result_ = std::move(a);
            emit ready();
          },
          Qt::QueuedConnection);
    } catch (const std::exception& e) {
      const QString error = QString::fromStdString(e.what());
      QMetaObject::invokeMethod(
          this, [this, error] { emit failed(error); }, Qt::QueuedConnection);
    }
  });
}

void AnalysisPage::show_result() {
  run_->setEnabled(true);
  if (!result_) return;
  const studies::StudyDatabaseAnalysis& a = *result_;
  document_ = studies::build_report(a);
  QStringList left_out;
  for (const auto& [id, why] : a.quality.left_out) left_out << text(id + " (" + why + ")");
  if (!a.completion_time)
    status_->setText(
        tr("Completion time not analysed: %1").arg(text(a.completion_time_not_computed)));
  else
    status_->setText(left_out.isEmpty()
                         ? tr("%1 participants analysed").arg(a.completion_time->n_subjects)
                         : tr("%1 participants analysed; left out: %2")
                               .arg(a.completion_time->n_subjects)
                               .arg(left_out.join("; ")));
  tables_->setHtml(report_html(*document_));
  figures_->set(&*result_, &*document_);
}

}  // namespace handlab::gui
