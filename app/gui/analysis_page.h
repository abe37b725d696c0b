// The Analysis view: the study's analysis (studies/analysis, the code of `analyze --db`) run
// off the window's thread, shown as the study report shows it (studies/report: the same
// text and tables; app/report: the same figures).
#pragma once

#include <memory>
#include <optional>
#include <thread>

#include <QWidget>

#include "studies/analysis/study_database_analysis.h"
#include "studies/report/report_document.h"

class QLabel;
class QPushButton;
class QTextBrowser;

namespace handlab::gui {

class FigurePanel;

class AnalysisPage : public QWidget {
  Q_OBJECT

 public:
  explicit AnalysisPage(QWidget* parent = nullptr);
  ~AnalysisPage() override;
  void set_study(const QString& database);
  // Starts the analysis in the background; `ready` or `failed` follows.
  void run();
  bool busy() const { return worker_.joinable(); }
  const std::optional<studies::StudyDatabaseAnalysis>& result() const { return result_; }
  QTextBrowser* tables() const { return tables_; }

 signals:
  void ready();
  void failed(QString error);

 protected:
  void showEvent(QShowEvent* event) override;  // runs the analysis when first shown

 private:
  void show_result();

  QString database_;
  QPushButton* run_ = nullptr;
  QLabel* status_ = nullptr;
  QTextBrowser* tables_ = nullptr;
  FigurePanel* figures_ = nullptr;
  std::optional<studies::StudyDatabaseAnalysis> result_;
  std::optional<studies::ReportDocument> document_;  // what the tables and figures show
  std::thread worker_;
};

}  // namespace handlab::gui
