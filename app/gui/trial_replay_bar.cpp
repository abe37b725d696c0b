#include "app/gui/trial_replay_bar.h"

#include <algorithm>

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QTimer>

#include "app/gui/trial_status_text.h"
#include "core/hand/simulated_hand.h"
#include "core/render/frame_drawing.h"

namespace handlab::gui {

TrialReplayBar::TrialReplayBar(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  label_ = new QLabel;
  play_ = new QPushButton(tr("Play"));
  play_->setObjectName("replay_play");
  slider_ = new QSlider(Qt::Horizontal);
  slider_->setObjectName("replay_slider");
  time_label_ = new QLabel;
  close_ = new QPushButton(tr("Close Replay"));
  layout->addWidget(label_);
  layout->addWidget(play_);
  layout->addWidget(slider_, 1);
  layout->addWidget(time_label_);
  layout->addWidget(close_);
  timer_ = new QTimer(this);
  timer_->setInterval(15);
  connect(timer_, &QTimer::timeout, this, &TrialReplayBar::tick);
  connect(play_, &QPushButton::clicked, this, [this] { set_playing(!playing_); });
  // Dragging or clicking the slider moves to that moment (and holds the playback there).
  connect(slider_, &QSlider::valueChanged, this, [this](int ms) {
    set_playing(false);
    seek(ms / 1000.0);
  });
  connect(close_, &QPushButton::clicked, this, [this] {
    set_playing(false);
    hide();
    emit closed();
  });
}

void TrialReplayBar::load(studies::TrialReplay replay) {
  set_playing(false);
  bones_ = render::make_bone_meshes(hand::build_simulated_hand(replay.simulated_hand));
  replay_ = std::move(replay);
  label_->setText(tr("Replay: %1, trial %2 (attempt %3), %4, %5")
                      .arg(QString::fromStdString(replay_->participant))
                      .arg(replay_->position + 1)
                      .arg(replay_->attempt)
                      .arg(QString::fromStdString(replay_->condition))
                      .arg(trial_status_text(replay_->status)));
  {
    const QSignalBlocker quiet(slider_);
    slider_->setRange(0, int(replay_->duration() * 1000.0 + 0.5));
    slider_->setValue(0);
  }
  seek(0.0);
  set_playing(true);
}

void TrialReplayBar::seek(double seconds) {
  if (!replay_) return;
  time_ = std::clamp(seconds, 0.0, replay_->duration());
  const store::FrameRecord& frame = replay_->frame_at(time_);
  auto picture = std::make_shared<const render::DrawList>(
      render::draw_stored_frame(replay_->layout, bones_, frame));
  show_time();
  emit moment(std::move(picture), frame);
}

void TrialReplayBar::set_playing(bool on) {
  on = on && replay_ && !replay_->frames.empty();
  if (on && time_ >= replay_->duration()) seek(0.0);  // Play at the end starts again
  playing_ = on;
  play_->setText(on ? tr("Pause") : tr("Play"));
  if (on) {
    clock_start_ = time_;
    clock_.start();
    timer_->start();
  } else {
    timer_->stop();
  }
}

void TrialReplayBar::tick() {
  if (!replay_) return;
  const double t = clock_start_ + clock_.nsecsElapsed() * 1e-9;
  seek(t);
  if (t >= replay_->duration()) set_playing(false);
}

void TrialReplayBar::show_time() {
  {
    const QSignalBlocker quiet(slider_);
    slider_->setValue(int(time_ * 1000.0 + 0.5));
  }
  time_label_->setText(
      tr("%1 / %2 s").arg(time_, 0, 'f', 2).arg(replay_ ? replay_->duration() : 0.0, 0, 'f', 2));
}

}  // namespace handlab::gui
