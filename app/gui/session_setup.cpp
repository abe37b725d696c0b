#include "app/gui/session_setup.h"

#include <exception>

#include <QCheckBox>
#include <QComboBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include "app/gui/headset_eyes.h"
#include "app/gui/leap_link.h"
#include "app/live/leap_websocket_client.h"
#include "app/live/live_frames.h"
#include "core/xr/openxr_runtime.h"

namespace handlab::gui {
namespace {

enum TrackerChoice { kLiveLeap, kRecording, kSimulated, kScripted, kOpenXrHands };
enum DisplayChoice { kWindow, kHeadset };

}  // namespace

SessionSetup::SessionSetup(QWidget* parent) : QGroupBox(tr("Set-up"), parent) {
  auto* form = new QFormLayout(this);
  participant_ = new QComboBox;
  participant_->setObjectName("participant");
  form->addRow(tr("Participant"), participant_);
  tracker_ = new QComboBox;
  tracker_->setObjectName("tracker");
  tracker_->addItem(tr("Live Leap Motion"), kLiveLeap);
  tracker_->addItem(tr("Recording file"), kRecording);
  tracker_->addItem(tr("Simulated participant"), kSimulated);
  tracker_->addItem(tr("Scripted participant"), kScripted);
  tracker_->addItem(tr("OpenXR hands"), kOpenXrHands);
  form->addRow(tr("Tracker"), tracker_);
  address_ = new QLineEdit("ws://127.0.0.1:6437");
  address_->setObjectName("leap_address");
  form->addRow(tr("Leap address"), address_);
  leap_state_ = new QLabel(tr("not connected"));
  leap_state_->setObjectName("leap_state");
  form->addRow(tr("Leap"), leap_state_);
  leap_ = new LeapLink(this);
  connect(leap_, &LeapLink::state_changed, leap_state_, &QLabel::setText);
  auto* file_row = new QHBoxLayout;
  recording_ = new QLineEdit;
  recording_->setObjectName("recording");
  recording_->setPlaceholderText(tr("a .json, .json.lz or .hlrec recording"));
  auto* browse = new QPushButton(tr("…"));
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Recording"), QString(),
                                                      tr("Recordings (*.json *.lz *.hlrec)"));
    if (!path.isEmpty()) recording_->setText(path);
  });
  file_row->addWidget(recording_);
  file_row->addWidget(browse);
  form->addRow(tr("Recording"), file_row);
  seed_ = new QSpinBox;
  seed_->setObjectName("seed");
  seed_->setRange(0, 1 << 30);
  form->addRow(tr("Population seed"), seed_);
  world_ = new QComboBox;
  world_->setObjectName("world");
  world_->addItem(tr("Soft hand (simulator)"), int(studies::WorldKind::kSoftHand));
  world_->addItem(tr("Grasp proxy"), int(studies::WorldKind::kGraspProxy));
  form->addRow(tr("World"), world_);
  display_ = new QComboBox;
  display_->setObjectName("display");
  display_->addItem(tr("Window"), kWindow);
  display_->addItem(tr("Headset (OpenXR)"), kHeadset);
  form->addRow(tr("Display"), display_);
  openxr_state_ = new QLabel(tr("not needed"));
  openxr_state_->setObjectName("openxr_state");
  openxr_state_->setWordWrap(true);
  form->addRow(tr("OpenXR"), openxr_state_);
  real_time_ = new QCheckBox(tr("Real time"));
  real_time_->setObjectName("real_time");
  real_time_->setChecked(true);
  form->addRow(QString(), real_time_);
  connect(tracker_, &QComboBox::currentIndexChanged, this, &SessionSetup::update_fields);
  connect(display_, &QComboBox::currentIndexChanged, this, &SessionSetup::update_fields);
  connect(address_, &QLineEdit::editingFinished, this, &SessionSetup::update_fields);
  update_fields();
}

SessionSetup::~SessionSetup() = default;

QString SessionSetup::tracker_name() const {
  return tracker_->currentText();
}

void SessionSetup::use_defaults(const studies::Protocol& protocol) {
  static const std::pair<const char*, TrackerChoice> kTrackers[] = {{"leap", kLiveLeap},
                                                                    {"openxr", kOpenXrHands},
                                                                    {"scripted", kScripted},
                                                                    {"simulated", kSimulated}};
  for (const auto& [name, choice] : kTrackers)
    if (protocol.default_tracker == name) tracker_->setCurrentIndex(tracker_->findData(choice));
  display_->setCurrentIndex(display_->findData(
      protocol.default_display == studies::SessionDisplay::kHeadset ? kHeadset : kWindow));
}

void SessionSetup::set_leap_address(const QString& address) {
  address_->setText(address);
  update_fields();
}

void SessionSetup::set_running(bool running) {
  running_ = running;
  participant_->setEnabled(!running);
  tracker_->setEnabled(!running);
  world_->setEnabled(!running);
  display_->setEnabled(!running);
  real_time_->setEnabled(!running);
  update_fields();
}

void SessionSetup::update_fields() {
  const int choice = tracker_->currentData().toInt();
  address_->setEnabled(!running_ && choice == kLiveLeap);
  recording_->setEnabled(choice == kRecording);
  seed_->setEnabled(choice == kSimulated);
  const bool headset = display_->currentData().toInt() == kHeadset;
  // In the headset the participant sees the trial as it happens.
  real_time_->setEnabled(!running_ && !headset);
  if (headset) real_time_->setChecked(true);
  if (headset || choice == kOpenXrHands) probe_openxr();
  // The running session reads the live client's frames: it stays.
  if (choice == kLiveLeap && !running_) leap_->connect_to(address_->text());
}

// Asked when first needed (the runtime is loaded to answer), until one is found.
void SessionSetup::probe_openxr() {
  if (openxr_found_) return;  // a runtime not found is asked again when next needed
  const xr::OpenXrRuntimeInfo info = xr::probe_openxr_runtime();
  openxr_found_ = info.found;
  if (!info.found) {
    openxr_state_->setText(tr("no runtime: %1").arg(QString::fromStdString(info.error)));
    return;
  }
  const QString headset =
      info.system_found ? QString::fromStdString(info.system_name)
                        : tr("no headset (%1)").arg(QString::fromStdString(info.system_error));
  openxr_state_->setText(tr("%1 %2; %3; %4")
                             .arg(QString::fromStdString(info.runtime_name),
                                  QString::fromStdString(info.runtime_version), headset,
                                  info.system_tracks_hands ? tr("tracks hands")
                                  : info.hand_tracking_extension
                                      ? tr("XR_EXT_hand_tracking, no hands on this headset")
                                      : tr("no hand tracking")));
}

QString SessionSetup::fill(SessionOptions& options, std::shared_ptr<live::LiveFrameStats>& live) {
  options.participant = participant_->currentText().toStdString();
  options.world = studies::WorldKind(world_->currentData().toInt());
  options.real_time = real_time_->isChecked();
  options.in_headset = display_->currentData().toInt() == kHeadset;
  if (options.in_headset) {
    try {
      if (!eyes_) eyes_ = std::make_unique<HeadsetEyes>();
    } catch (const std::exception& e) {
      return QString::fromStdString(e.what());
    }
    options.headset_eyes = eyes_->factory();
  }
  live.reset();
  switch (tracker_->currentData().toInt()) {
    case kLiveLeap: {
      update_fields();
      if (!leap_->client()) return tr("the Leap client cannot change while a session runs");
      live = std::make_shared<live::LiveFrameStats>();
      live::FrameQueue* queue = &leap_->client()->queue();
      auto stats = live;
      options.tracker = studies::live_tracker(
          "leap " + address_->text().toStdString(),
          [queue, stats] { return std::make_unique<live::LiveFrames>(*queue, stats); });
      options.frame_arrival = [stats] { return stats->last_arrival_ns.load(); };
      break;
    }
    case kRecording:
      if (recording_->text().isEmpty()) return tr("choose a recording file");
      try {
        options.tracker = studies::recording_tracker(recording_->text().toStdString());
      } catch (const std::exception& e) {
        return QString::fromStdString(e.what());
      }
      break;
    case kSimulated:
      options.tracker = studies::simulated_tracker(std::uint64_t(seed_->value()));
      break;
    case kOpenXrHands:
      options.openxr_hands = true;  // the tracker made when the session opens the runtime
      break;
    default:
      options.tracker = studies::scripted_tracker();
  }
  return {};
}

}  // namespace handlab::gui
