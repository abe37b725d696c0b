// The session screen: set-up (participant, tracker, world), the open-palm calibration, the
// live 3D view and the experimenter's trial panel with Start / Pause / Stop, Redo and Skip.
// It runs a SessionWorker (studies/session, as `handlab-cli session run`) and mirrors the
// scene into the participant's window, which never shows the condition.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <QWidget>

#include "app/gui/display_latency.h"
#include "app/gui/open_study.h"
#include "app/gui/session_setup.h"
#include "core/hand/hand_shape.h"
#include "core/render/hand_drawing.h"
#include "studies/protocol/protocol.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;
class QSpinBox;
class QThread;
class QTimer;
class QStackedWidget;

namespace handlab::live {
struct LiveFrameStats;
}  // namespace handlab::live

namespace handlab::gui {

class ParticipantWindow;
class QuestionnaireForm;
class SceneView;
class SessionWorker;
class TrialReplayBar;

class SessionPage : public QWidget {
  Q_OBJECT

 public:
  explicit SessionPage(QWidget* parent = nullptr);
  ~SessionPage() override;

  // The study the sessions run in (empty: none open).
  void set_study(OpenStudy study);
  void set_participants(const QStringList& ids, const QString& selected = {});
  SceneView* view() const { return view_; }
  bool session_running() const;
  // The open study's protocol (none: no study open).
  const std::optional<studies::Protocol>& protocol() const { return protocol_; }
  SessionWorker* worker() const { return worker_.get(); }
  void set_participant_window(ParticipantWindow* window);

  // The actions behind the buttons (the shortcuts and the tests use them). Each returns the
  // reason when it cannot act (empty: done or requested).
  QString start_session();
  // As if typed into the address field: the live client reconnects there.
  void set_leap_address(const QString& address);
  void toggle_pause();
  void stop_session();
  QString redo_trial(int position, const QString& reason);
  QString skip_trial(int position, const QString& reason);
  // Plays a stored trial back in the view from its frame log (`position` 0-based; attempt 0:
  // the latest with frames); not while a session runs.
  QString replay_trial(const QString& participant, int position, int attempt = 0);

  // The widgets, by role (for tests and screenshots).
  QComboBox* participant_box() const { return setup_->participant_box(); }
  QComboBox* tracker_box() const { return setup_->tracker_box(); }
  QComboBox* world_box() const { return setup_->world_box(); }
  // Where the participant looks: their window (or this one) or the OpenXR headset.
  QComboBox* display_box() const { return setup_->display_box(); }
  QLineEdit* recording_edit() const { return setup_->recording_edit(); }
  // Off: the session runs as fast as the pipeline goes (a replay or a simulated participant
  // needs no wall clock; a live tracker always runs in real time).
  QCheckBox* real_time_box() const { return setup_->real_time_box(); }
  QPushButton* start_button() const { return start_; }
  QLabel* calibration_label() const { return calibration_; }
  QLabel* state_label() const { return state_; }
  QListWidget* log() const { return log_; }
  // The questions awaiting answers: in a dialog over this window, or in the participant's
  // window when it is open; null between questionnaires.
  QuestionnaireForm* questionnaire() const { return questionnaire_; }
  TrialReplayBar* replay_bar() const { return replay_; }

  // The display's figures, for docs/performance.md (display_latency.h).
  using DisplayStats = gui::DisplayStats;
  DisplayStats display_stats() const;
  // Starts the figures afresh (a measurement leaves out the session's start).
  void reset_display_stats();

 signals:
  void session_started();
  void session_ended(QString summary);
  void study_changed();  // a trial's result, a decision: the participants view refreshes
  void questionnaire_opened(QuestionnaireForm* form);

 private:
  void connect_worker(SessionWorker* w);
  void refresh_picture();
  void show_questionnaire(int position, const QString& condition);
  void set_running(bool running);
  void append_log(const QString& line);
  // In the headset, the instruction on its panel (when it changes).
  void show_in_headset(const QString& instruction);
  void mirror_headset();

  OpenStudy study_;
  std::optional<studies::Protocol> protocol_;
  SceneView* view_ = nullptr;
  TrialReplayBar* replay_ = nullptr;
  SessionSetup* setup_ = nullptr;
  QLabel *calibration_ = nullptr, *trial_ = nullptr, *state_ = nullptr, *clock_ = nullptr,
         *counts_ = nullptr;
  QPushButton *start_ = nullptr, *pause_ = nullptr, *stop_ = nullptr, *redo_ = nullptr,
              *skip_ = nullptr;
  QListWidget* log_ = nullptr;
  std::unique_ptr<SessionWorker> worker_;
  std::shared_ptr<live::LiveFrameStats> live_stats_;
  ParticipantWindow* participant_window_ = nullptr;
  QuestionnaireForm* questionnaire_ = nullptr;
  // The condition's hand, rebuilt when a trial of another hand starts.
  render::BoneMeshes hand_meshes_;
  hand::HandShape hand_shape_;
  long last_drawn_step_ = -1;
  QString headset_text_;  // the instruction on the headset's panel
  QLabel* headset_mirror_ = nullptr;
  QTimer* mirror_timer_ = nullptr;
  DisplayLatency display_;
};

}  // namespace handlab::gui
