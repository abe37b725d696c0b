// The session screen's set-up form: the participant, the tracker (a live Leap at an address,
// a recording, a simulated or a scripted participant, the OpenXR runtime's hands), the
// participant's display (a window or the OpenXR headset), the world and the pace. It turns
// what is chosen into the session's options, keeps the live client connected while the live
// tracker is chosen, and says which OpenXR runtime is there while one is needed.
#pragma once

#include <memory>

#include <QGroupBox>

#include "app/gui/session_worker.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QSpinBox;

namespace handlab::live {
struct LiveFrameStats;
}  // namespace handlab::live

namespace handlab::gui {

class HeadsetEyes;
class LeapLink;

class SessionSetup : public QGroupBox {
  Q_OBJECT

 public:
  explicit SessionSetup(QWidget* parent = nullptr);
  ~SessionSetup() override;

  QComboBox* participant_box() const { return participant_; }
  QComboBox* tracker_box() const { return tracker_; }
  QComboBox* world_box() const { return world_; }
  QComboBox* display_box() const { return display_; }
  QLabel* openxr_label() const { return openxr_state_; }
  QLineEdit* recording_edit() const { return recording_; }
  QCheckBox* real_time_box() const { return real_time_; }
  QString tracker_name() const;

  // The study's defaults ("session" in its protocol): the tracker and display it names.
  void use_defaults(const studies::Protocol& protocol);
  // As if typed into the address field: the live client reconnects there.
  void set_leap_address(const QString& address);
  // While a session runs nothing can be changed (the session reads the live client's frames).
  void set_running(bool running);
  // The tracker, world and pace chosen, into `options`; with the live tracker, `live` counts
  // its frames. The reason when they cannot be.
  QString fill(SessionOptions& options, std::shared_ptr<live::LiveFrameStats>& live);

 private:
  void update_fields();
  void probe_openxr();

  LeapLink* leap_ = nullptr;  // its client made when the live tracker is chosen
  bool running_ = false;
  QComboBox *participant_ = nullptr, *tracker_ = nullptr, *world_ = nullptr, *display_ = nullptr;
  QLineEdit *address_ = nullptr, *recording_ = nullptr;
  QLabel *leap_state_ = nullptr, *openxr_state_ = nullptr;
  bool openxr_found_ = false;
  std::unique_ptr<HeadsetEyes> eyes_;  // made when the headset is first chosen
  QSpinBox* seed_ = nullptr;
  QCheckBox* real_time_ = nullptr;
};

}  // namespace handlab::gui
