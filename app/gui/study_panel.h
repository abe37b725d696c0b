// A study database at a glance: per participant, the trials planned, completed (by success
// or timeout), skipped and aborted, and the next trial — what `handlab-cli study status`
// prints, refreshed while sessions run.
#pragma once

#include <QString>
#include <QWidget>

class QLabel;
class QTableWidget;

namespace handlab::gui {

class StudyPanel : public QWidget {
  Q_OBJECT

 public:
  explicit StudyPanel(QWidget* parent = nullptr);
  // Reads the database; on failure shows and returns the one-line reason (empty: success).
  QString open_database(const QString& path);
  void refresh();
  QTableWidget* table() const { return table_; }

 private:
  QString path_;
  QLabel* title_ = nullptr;
  QTableWidget* table_ = nullptr;
};

}  // namespace handlab::gui
