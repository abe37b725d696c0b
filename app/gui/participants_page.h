// The enrolled participants (id, age, sex, handedness, hand length in cm, VR experience,
// notes, trials done of planned, status), Add and Edit through the form, and the selected
// participant's stored schedule: block by block, the condition of every trial, its status
// and result, practice marked.
#pragma once

#include <QWidget>

#include "app/gui/open_study.h"

class QPushButton;
class QTableView;
class QLabel;

namespace handlab::gui {

class TextTableModel;

class ParticipantsPage : public QWidget {
  Q_OBJECT

 public:
  explicit ParticipantsPage(QWidget* parent = nullptr);
  void set_study(OpenStudy study);  // not open: none
  // Reads the database again; selects `select_id` (default: the selected participant).
  void refresh(const QString& select_id = {});
  QStringList ids() const;  // the enrolled, in the table's order
  // Opens the form; returns the id enrolled or changed (empty: cancelled or refused).
  QString add_participant();
  QString edit_participant();
  QString selected() const;
  void select(const QString& id);
  // The session page's running participant shows as "in session", not "interrupted".
  void set_in_session(const QString& id) {
    in_session_ = id;
    refresh();
  }

  QTableView* table() const { return table_; }
  QTableView* schedule() const { return schedule_; }
  const TextTableModel& participant_rows() const { return *participants_; }
  const TextTableModel& schedule_rows() const { return *trials_; }
  QPushButton* add_button() const { return add_; }
  QPushButton* replay_button() const { return replay_; }

 signals:
  void participants_changed(QStringList ids, QString selected);
  // Replay Trial, or a double-click on a trial that ran (`position` 0-based).
  void replay_requested(QString participant, int position);

 private:
  void show_schedule();
  int selected_row() const;
  // A trial that ran (its status is not "planned") can be played back.
  bool trial_ran(int row) const;

  OpenStudy study_;
  QString in_session_;
  TextTableModel* participants_ = nullptr;
  TextTableModel* trials_ = nullptr;
  QTableView* table_ = nullptr;
  QTableView* schedule_ = nullptr;
  QLabel* schedule_title_ = nullptr;
  QPushButton *add_ = nullptr, *edit_ = nullptr, *replay_ = nullptr;
};

}  // namespace handlab::gui
