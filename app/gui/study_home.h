// The study home: without a study, New Study and Open Study with the recent files; with one,
// its file, its protocol in a few lines, the participants' progress, and any interrupted
// session with the trial where it resumes.
#pragma once

#include <QWidget>

#include "app/gui/open_study.h"

class QLabel;
class QListWidget;
class QPushButton;
class QTableView;

namespace handlab::gui {

class TextTableModel;

class StudyHome : public QWidget {
  Q_OBJECT

 public:
  explicit StudyHome(QWidget* parent = nullptr);
  // Not open: none. `own_session`: the participant whose session this app runs now (not
  // interrupted, though its session is open in the database).
  void set_study(OpenStudy study, const QString& own_session = {});
  void set_recent(const QStringList& files);
  QStringList interrupted() const { return interrupted_; }  // participant ids
  QLabel* interrupted_label() const { return interrupted_label_; }
  QPushButton* resume_button() const { return resume_; }
  QTableView* summary() const { return summary_; }
  const TextTableModel& summary_rows() const { return *summary_rows_; }

 signals:
  void new_study_requested();
  void open_study_requested();
  void open_recent_requested(QString path);
  void resume_requested(QString participant);

 private:
  OpenStudy study_;
  QStringList interrupted_;
  QLabel *title_ = nullptr, *interrupted_label_ = nullptr;
  QPushButton* resume_ = nullptr;
  TextTableModel* summary_rows_ = nullptr;
  QTableView* summary_ = nullptr;
  QListWidget* recent_ = nullptr;
  QWidget *none_ = nullptr, *open_ = nullptr;
};

}  // namespace handlab::gui
