// A participant's session run from the app: the same SessionRunner and PipelineTrialDriver
// as `handlab-cli session run`, on a thread of their own with their own database
// connection, paced in real time. The window steers it through its SessionControl and
// reads the newest step from a snapshot when told one is there (step_ready, at most one
// waiting, so a slow display skips steps rather than falling behind); the questionnaire is asked
// on the window's thread while the session thread waits for the answers.
#pragma once

#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>

#include <QObject>
#include <QString>

#include "core/hand/flesh.h"
#include "core/store/frame_record.h"
#include "core/xr/headset_view.h"
#include "studies/protocol/protocol.h"
#include "studies/session/session_control.h"
#include "studies/session/session_headset.h"
#include "studies/session/trial_driver.h"

namespace handlab::gui {

struct SessionOptions {
  QString database;            // opened again on the session's thread
  studies::Protocol protocol;  // the study's, as the window read it
  std::string participant;
  // A simulated participant answers the questionnaires itself; otherwise the dialog asks.
  studies::TrackerPtr tracker = studies::scripted_tracker();
  studies::WorldKind world = studies::WorldKind::kSoftHand;
  bool resume = false;
  bool real_time = true;
  // With a live tracker: when the frame a step used arrived (steady clock, ns), read on the
  // session thread right after the step, for the display's latency.
  std::function<long long()> frame_arrival;
  // The participant in the OpenXR headset, its eyes drawn by `headset_eyes` (HeadsetEyes);
  // the session then runs in real time.
  bool in_headset = false;
  xr::HeadsetView::DrawerFactory headset_eyes;
  // The OpenXR runtime's hands as the tracker (made when the session starts: from the
  // headset's own session in the headset), in place of `tracker`.
  bool openxr_hands = false;
};

// The soft hand's skin as the views draw it: the flesh's render surface and tets (no state:
// copied once per simulated hand and cube).
struct SoftHandSkin {
  hand::EmbeddedSurface surface;
  mesh::TetMesh tets;
};

// What the view and the trial panel show of the session at one moment.
struct SessionSnapshot {
  bool in_trial = false;
  int position = 0, planned = 0, block = 0;
  bool practice = false;
  std::string condition;
  double cube_size = 0.06;
  hand::HandShape simulated_hand;
  studies::TrialStep step;   // step's pointers are null here; the record is `frame`
  store::FrameRecord frame;  // the newest step's
  // On the soft hand, its skin and the flesh's nodes after the newest step (else empty).
  std::shared_ptr<const SoftHandSkin> skin;
  std::vector<Eigen::Vector3d> flesh_nodes;
  long steps = 0;  // counted over the session
  std::chrono::steady_clock::time_point stepped_at;
  long long frame_arrival_ns = 0;  // with a live tracker
  // While calibrating.
  std::optional<studies::CalibrationStatus> calibration;
};

class SessionWorker : public QObject {
  Q_OBJECT

 public:
  explicit SessionWorker(SessionOptions options, QObject* parent = nullptr);
  ~SessionWorker() override;  // stops the session and waits for its thread

  // Opens the headset and the OpenXR hands where chosen (throws std::runtime_error, with the
  // reason, where they cannot be), then starts the session's thread.
  void start();
  bool running() const { return thread_.joinable() && !finished_; }
  studies::SessionControl& control() { return control_; }
  // The newest step; the next one after this call emits step_ready again.
  SessionSnapshot snapshot() const;
  const studies::Protocol& protocol() const { return options_.protocol; }
  // The questionnaire's answers for the trial that asked (one per item, 1..scale).
  void answer(std::vector<int> values);
  // In the headset: what it has shown so far (null otherwise), and its last frame's images.
  std::optional<xr::HeadsetCounts> headset_counts() const;
  std::optional<xr::DisplayFrame> headset_frame() const;
  bool in_headset() const { return headset_ != nullptr; }
  // In the headset: the picture on the panel before the participant (SessionHeadset).
  void set_headset_panel(std::shared_ptr<const render::Image> picture);

 signals:
  void step_ready();  // a step or a calibration frame to show
  void calibration_changed(QString message, bool done);
  void trial_started(int position);
  void trial_ended(int position, bool success, double seconds, bool aborted);
  void questionnaire_requested(int position, QString condition);
  void decided(QString message);
  void holding();
  void finished(bool complete, bool stopped, int trials_run);
  void failed(QString error);
  // The headset changed what the session does (taken off, back, its runtime gone).
  void headset_said(QString message);

 private:
  void run();

  SessionOptions options_;
  studies::SessionControl control_;
  mutable std::mutex mutex_;
  SessionSnapshot snapshot_;
  const hand::HandFlesh* skin_of_ = nullptr;  // the flesh `skin_` was copied from
  std::shared_ptr<const SoftHandSkin> skin_;  // session thread only
  std::mutex answer_mutex_;
  std::optional<std::promise<std::vector<int>>> pending_answer_;
  std::unique_ptr<studies::SessionHeadset> headset_;  // its loop runs on a thread of its own
  std::atomic<bool> finished_{false}, closing_{false};
  mutable std::atomic<bool> step_waiting_{false};
  std::thread thread_;
};

}  // namespace handlab::gui
