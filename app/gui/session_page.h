// The session screen: set-up (participant, tracker, world), the open-palm calibration, the
// live 3D view and the experimenter's trial panel with Start / Pause / Stop, Redo and Skip.
// It runs a SessionWorker (studies/session, as `handlab-cli session run`) and mirrors the
// scene into the participant's window, which never shows the condition.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include <QWidget>

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
class QStackedWidget;

namespace handlab::live {
class LeapWebSocketClient;
struct LiveFrameStats;
}  // namespace handlab::live

namespace handlab::gui {

class ParticipantWindow;
class QuestionnaireDialog;
class SceneView;
class SessionWorker;
class TrialReplayBar;

class SessionPage : public QWidget {
  Q_OBJECT

 public:
  explicit SessionPage(QWidget* parent = nullptr);
  ~SessionPage() override;

  // The study the sessions run in (empty: none open).
  void set_study(const QString& database);
  void set_participants(const QStringList& ids, const QString& selected = {});
  SceneView* view() const { return view_; }
  bool session_running() const;
  SessionWorker* worker() const { return worker_.get(); }
  void set_participant_window(ParticipantWindow* window) { participant_window_ = window; }

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
  QComboBox* participant_box() const { return participant_; }
  QComboBox* tracker_box() const { return tracker_; }
  QComboBox* world_box() const { return world_; }
  QLineEdit* address_edit() const { return address_; }
  QLineEdit* recording_edit() const { return recording_; }
  QSpinBox* seed_box() const { return seed_; }
  // Off: the session runs as fast as the pipeline goes (a replay or a simulated participant
  // needs no wall clock; a live tracker always runs in real time).
  QCheckBox* real_time_box() const { return real_time_; }
  QPushButton* start_button() const { return start_; }
  QPushButton* pause_button() const { return pause_; }
  QPushButton* stop_button() const { return stop_; }
  QLabel* calibration_label() const { return calibration_; }
  QLabel* trial_label() const { return trial_; }
  QLabel* state_label() const { return state_; }
  QListWidget* log() const { return log_; }
  QuestionnaireDialog* questionnaire() const { return questionnaire_; }
  TrialReplayBar* replay_bar() const { return replay_; }

  // The display's figures, for docs/performance.md. Latency: per live frame, from its
  // arrival to the swap of the first picture of a state simulated from it (other trackers:
  // from the step; a frame whose state a newer one replaced before the display took it is
  // not counted); pictures and seconds count the pictures of new steps and the time
  // between them (not the pauses between trials).
  struct DisplayStats {
    std::vector<double> latency_ms;
    std::vector<double> pipeline_ms;  // of which until the simulated state was there
    long pictures = 0;
    double seconds = 0;
    long frames_used = 0, frames_superseded = 0;  // live frames a step took, or never took
  };
  DisplayStats display_stats() const;
  // Starts the figures afresh (a measurement leaves out the session's start).
  void reset_display_stats();

 signals:
  void session_started();
  void session_ended(QString summary);
  void study_changed();  // a trial's result, a decision: the participants view refreshes
  void questionnaire_opened(QuestionnaireDialog* dialog);

 private:
  void update_tracker_fields();
  void refresh_picture();
  void picture_shown();
  void show_questionnaire(int position, const QString& condition);
  void set_running(bool running);
  void append_log(const QString& line);
  void ensure_leap_client();
  void drop_leap_client();

  QString database_;
  std::optional<studies::Protocol> protocol_;
  SceneView* view_ = nullptr;
  TrialReplayBar* replay_ = nullptr;
  QComboBox *participant_ = nullptr, *tracker_ = nullptr, *world_ = nullptr;
  QLineEdit *address_ = nullptr, *recording_ = nullptr;
  QSpinBox* seed_ = nullptr;
  QCheckBox* real_time_ = nullptr;
  QLabel *leap_state_ = nullptr, *calibration_ = nullptr, *trial_ = nullptr, *state_ = nullptr,
         *clock_ = nullptr, *counts_ = nullptr;
  QPushButton *start_ = nullptr, *pause_ = nullptr, *stop_ = nullptr, *redo_ = nullptr,
              *skip_ = nullptr;
  QListWidget* log_ = nullptr;
  std::unique_ptr<SessionWorker> worker_;
  // The Leap client on its thread (made when the live tracker is chosen) and what it said.
  QThread* leap_thread_ = nullptr;
  live::LeapWebSocketClient* leap_ = nullptr;
  QString leap_address_;
  bool leap_connected_ = false, leap_streaming_ = false, leap_hand_ = false;
  std::shared_ptr<live::LiveFrameStats> live_stats_;
  ParticipantWindow* participant_window_ = nullptr;
  QuestionnaireDialog* questionnaire_ = nullptr;
  // The condition's hand, rebuilt when a trial of another hand starts.
  render::BoneMeshes hand_meshes_;
  hand::HandShape hand_shape_;
  long last_drawn_step_ = -1;
  DisplayStats stats_;
  long used_before_ = 0, superseded_before_ = 0;  // live counts at the last reset
  // A new step's picture waits for its swap; when its frame arrived (or its step ran), if
  // that frame was not shown before.
  bool picture_waiting_ = false;
  std::optional<std::chrono::steady_clock::time_point> pending_origin_;
  long long pending_arrival_ns_ = 0, shown_arrival_ns_ = 0;
  std::chrono::steady_clock::time_point pending_stepped_;
  std::optional<std::chrono::steady_clock::time_point> last_shown_;
};

}  // namespace handlab::gui
