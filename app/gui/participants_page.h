// The enrolled participants (id, age, sex, handedness, hand length in cm, VR experience,
// notes, trials done of planned, status), Add and Edit through the form, and the selected
// participant's stored schedule: block by block, the condition of every trial, its status
// and result, practice marked.
#pragma once

#include <QWidget>

class QPushButton;
class QTableWidget;
class QLabel;

namespace handlab::gui {

class ParticipantsPage : public QWidget {
  Q_OBJECT

 public:
  explicit ParticipantsPage(QWidget* parent = nullptr);
  void set_study(const QString& database);  // empty: none
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

  QTableWidget* table() const { return table_; }
  QTableWidget* schedule() const { return schedule_; }
  QPushButton* add_button() const { return add_; }
  QPushButton* replay_button() const { return replay_; }

 signals:
  void participants_changed(QStringList ids, QString selected);
  // Replay Trial, or a double-click on a trial that ran (`position` 0-based).
  void replay_requested(QString participant, int position);

 private:
  void show_schedule();

  QString database_, in_session_;
  QTableWidget* table_ = nullptr;
  QTableWidget* schedule_ = nullptr;
  QLabel* schedule_title_ = nullptr;
  QPushButton *add_ = nullptr, *edit_ = nullptr, *replay_ = nullptr;
};

}  // namespace handlab::gui
