#include "app/gui/analysis_page.h"

#include <cmath>

#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSplitter>
#include <QTextBrowser>
#include <QVBoxLayout>

#include "analysis/report/analysis_output.h"
#include "app/gui/figures.h"
#include "core/store/study_store.h"
#include "studies/session/session_runner.h"

namespace handlab::gui {

// The figures, stacked, painted by figures.cpp.
class FigurePanel : public QWidget {
 public:
  explicit FigurePanel(QWidget* parent = nullptr) : QWidget(parent) {
    setMinimumSize(520, 1200);
    setObjectName("figures");
  }
  void set(const studies::StudyDatabaseAnalysis* a, int scale) {
    analysis_ = a;
    scale_ = scale;
    update();
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(rect(), Qt::white);
    if (!analysis_) {
      p.drawText(rect(), Qt::AlignCenter, tr("Run the analysis to see the figures."));
      return;
    }
    const double h = height() / 4.0;
    paint_time_by_condition(p, QRectF(10, 0, width() - 20, h - 10), analysis_->time_by_condition);
    for (std::size_t k = 0; k < analysis_->time_by_repetition.size() && k < 2; ++k)
      paint_time_by_repetition(p, QRectF(10, h * double(k + 1), width() - 20, h - 10),
                               QString::fromStdString(analysis_->time_by_repetition[k].first),
                               analysis_->time_by_repetition[k].second);
    paint_items(p, QRectF(10, h * 3, width() - 20, h - 10), analysis_->items_by_condition, scale_);
  }

 private:
  const studies::StudyDatabaseAnalysis* analysis_ = nullptr;
  int scale_ = 5;
};

namespace {

QString num(double x, int decimals = 2) {
  return std::isfinite(x) ? QString::number(x, 'f', decimals) : QString("–");
}
QString p_text(double p) {
  return QString::fromStdString(analysis::apa_p(p));
}
QString text(const std::string& s) {
  return QString::fromStdString(s);
}

// An HTML table: the header's markup kept (<sub>), every cell escaped ("p < .001", a level
// name with "<" in it).
QString html_table(const QStringList& header, const std::vector<QStringList>& rows) {
  QString html = "<table border=1 cellspacing=0 cellpadding=3><tr>";
  for (const QString& h : header) html += "<th>" + h + "</th>";
  html += "</tr>";
  for (const QStringList& row : rows) {
    html += "<tr>";
    for (const QString& cell : row) html += "<td>" + cell.toHtmlEscaped() + "</td>";
    html += "</tr>";
  }
  return html + "</table>";
}

QString anova_table(const analysis::AnalysisReport& r) {
  std::vector<QStringList> rows;
  for (const auto& e : r.anova.effects) {
    const bool tested = std::isfinite(e.mauchly_p);
    rows.push_back({text(e.effect),
                    text(analysis::apa_df(e.df_num)) + ", " + text(analysis::apa_df(e.df_den)),
                    num(e.f), p_text(e.p), num(e.ges, 3),
                    tested ? num(e.mauchly_w, 3) + " (" + p_text(e.mauchly_p) + ")" : "–",
                    tested ? num(e.eps_gg, 3) : "–", tested ? p_text(e.p_gg) : "–"});
  }
  return html_table({"Effect", "df", "F", "p", "η²<sub>G</sub>", "Mauchly W (p)", "ε<sub>GG</sub>",
                     "p<sub>GG</sub>"},
                    rows);
}

QString posthoc_table(const analysis::AnalysisReport& r) {
  QString html;
  for (const auto& ph : r.posthoc) {
    if (ph.contrasts.empty()) continue;
    html += QString("<p><b>%1</b> (Tukey-adjusted)</p>")
                .arg(text(ph.contrasts.front().effect).toHtmlEscaped());
    std::vector<QStringList> rows;
    for (const auto& c : ph.contrasts) {
      QString by;
      for (const auto& [f, l] : c.by) by += QString(" | %1 = %2").arg(text(f), text(l));
      rows.push_back({text(c.contrast) + by, num(c.estimate), num(c.se),
                      num(c.t) + "(" + text(analysis::apa_df(c.df)) + ")", p_text(c.p_tukey)});
    }
    html += html_table({"Contrast", "Estimate", "SE", "t(df)", "p<sub>Tukey</sub>"}, rows);
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
  figures_->set(nullptr, 5);
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
  int scale = 5;
  {
    store::StudyStore store(database_.toStdString());
    scale = studies::stored_protocol(store).scale_points;
  }
  QStringList left_out;
  for (const std::string& id : a.completion_time.dropped_subjects) left_out << text(id);
  status_->setText(left_out.isEmpty()
                       ? tr("%1 participants analysed").arg(a.completion_time.n_subjects)
                       : tr("%1 participants analysed; left out, lacking a result in some cell: %2")
                             .arg(a.completion_time.n_subjects)
                             .arg(left_out.join(", ")));
  QString html = QString("<h2>%1</h2>").arg(text(a.study.name).toHtmlEscaped());
  html += tr("<h3>Completion time per condition</h3>");
  std::vector<QStringList> conditions;
  for (const auto& c : a.time_by_condition) {
    QStringList levels;
    for (const auto& l : c.levels) levels << text(l);
    conditions.push_back({levels.join(" "), QString::number(c.n), num(c.mean), num(c.se)});
  }
  html += html_table({"Condition", "n", "Mean (s)", "SE"}, conditions);
  html += tr("<h3>Repeated-measures ANOVA</h3>") + anova_table(a.completion_time);
  html += tr("<h3>Post hoc comparisons</h3>") + posthoc_table(a.completion_time);
  if (a.questionnaire) {
    std::vector<QStringList> friedman, wilcoxon;
    for (const auto& f : a.questionnaire->friedman)
      friedman.push_back({text(f.dv), num(f.result.chisq) + "(" + num(f.result.df, 0) + ")",
                          p_text(f.result.p), num(f.result.kendall_w, 3),
                          QString::number(f.result.n)});
    for (const auto& w : a.questionnaire->wilcoxon)
      wilcoxon.push_back({text(w.dv), text(w.contrast), num(w.result.v, 1), p_text(w.result.p),
                          p_text(w.p_bonferroni)});
    html += tr("<h3>Questionnaire: Friedman tests</h3>") +
            html_table({"Item", "χ²(df)", "p", "Kendall W", "n"}, friedman);
    html += tr("<h3>Questionnaire: Wilcoxon signed-rank tests (Bonferroni)</h3>") +
            html_table({"Item", "Contrast", "V", "p", "p<sub>Bonferroni</sub>"}, wilcoxon);
  }
  if (!a.completion_time.warnings.empty()) {
    html += tr("<h3>Warnings</h3><ul>");
    for (const auto& w : a.completion_time.warnings)
      html += "<li>" + QString::fromStdString(w).toHtmlEscaped() + "</li>";
    html += "</ul>";
  }
  tables_->setHtml(html);
  figures_->set(&*result_, scale);
}

}  // namespace handlab::gui
