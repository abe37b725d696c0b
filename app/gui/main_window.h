// The experimenter's window: the study home, the participants with their schedules, the
// session (set-up, calibration, trials, questionnaires) and the analysis, one tab each; the
// participant's window on demand. Every action goes through studies/ and analysis/, the
// code the CLI runs.
#pragma once

#include <QMainWindow>

#include "app/gui/open_study.h"

class QTabWidget;

namespace handlab::gui {

class AnalysisPage;
class ParticipantsPage;
class ParticipantWindow;
class PinchSimulation;
class SceneView;
class SessionPage;
class StudyHome;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens a study database (the title names it; recent files remember it); returns the
  // error text (empty: opened).
  QString open_study(const QString& path);
  // Creates a study database from a protocol file and opens it; returns the error text.
  QString create_study(const QString& protocol, const QString& database);
  // Kept for `handlab --study`: opens the study and shows its participants.
  QString show_study(const QString& path);
  QString study_path() const { return study_.path; }

  enum class Table { kTrials, kQuestionnaire, kFrames };
  // Writes trials.csv, questionnaire.csv or frames.csv of the open study (studies::write_*_csv,
  // as `handlab-cli export`); returns the error text.
  QString export_table(const QString& path, Table table);
  // report.html and report.pdf of the open study into `folder` (as `handlab-cli report`);
  // returns an error message, empty on success.
  QString export_report(const QString& folder);
  // Reads a CSV file (RFC 4180) into a table dock; returns the error text.
  QString open_data_table(const QString& path);

  ParticipantWindow* show_participant_window(int screen = -1);

  StudyHome* home() const { return home_; }
  ParticipantsPage* participants() const { return participants_; }
  SessionPage* session() const { return session_; }
  AnalysisPage* analysis() const { return analysis_; }
  QTabWidget* tabs() const { return tabs_; }
  ParticipantWindow* participant_window() const { return participant_window_; }

  SceneView* scene_view() const;
  // The scripted pinch-and-lift of the current cube in the view, up to `until` seconds (the
  // script's end when 0); null when none runs.
  PinchSimulation* start_pinch(double until = 0.0);
  PinchSimulation* pinch() const { return pinch_; }
  void stop_pinch();
  void set_show_contacts(bool show);

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  void build_menus();
  void new_study_dialog();
  void open_study_dialog();
  void export_dialog(Table table);
  void export_report_dialog();
  void open_data_table_dialog();
  void save_view_image();
  void set_cube_size(double metres);
  void show_about();
  void show_pinch_state();
  void remember_recent(const QString& path);
  void refresh_study();
  void show_error(const QString& title, const QString& error);

  OpenStudy study_;  // its store shared with the pages
  QTabWidget* tabs_ = nullptr;
  StudyHome* home_ = nullptr;
  ParticipantsPage* participants_ = nullptr;
  SessionPage* session_ = nullptr;
  AnalysisPage* analysis_ = nullptr;
  ParticipantWindow* participant_window_ = nullptr;
  QMenu* recent_menu_ = nullptr;
  PinchSimulation* pinch_ = nullptr;
  bool show_contacts_ = false;
};

}  // namespace handlab::gui
