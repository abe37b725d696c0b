// The bar under the session view that plays a stored trial back (studies::TrialReplay, from
// the frame log): Play / Pause, a slider to any moment, the time and which trial it is. It
// draws each moment as the live view would draw that step (the bones: the log has no flesh)
// and hands the picture to the view; the trial panel shows the task's state of that moment.
#pragma once

#include <memory>
#include <optional>

#include <QElapsedTimer>
#include <QWidget>

#include "core/render/draw_list.h"
#include "core/render/hand_drawing.h"
#include "studies/session/trial_replay.h"

class QLabel;
class QPushButton;
class QSlider;
class QTimer;

namespace handlab::gui {

class TrialReplayBar : public QWidget {
  Q_OBJECT

 public:
  explicit TrialReplayBar(QWidget* parent = nullptr);

  // Shows the trial's first moment and plays it at its own pace.
  void load(studies::TrialReplay replay);
  void seek(double seconds);
  void set_playing(bool on);
  bool playing() const { return playing_; }
  double time() const { return time_; }
  const studies::TrialReplay* replay() const { return replay_ ? &*replay_ : nullptr; }

  QSlider* slider() const { return slider_; }
  QPushButton* play_button() const { return play_; }
  QLabel* label() const { return label_; }
  QPushButton* close_button() const { return close_; }

 signals:
  // A moment to show: its picture and the record it was drawn from.
  void moment(std::shared_ptr<const render::DrawList> picture, const store::FrameRecord& frame);
  void closed();

 private:
  void tick();
  void show_time();

  std::optional<studies::TrialReplay> replay_;
  render::BoneMeshes bones_;
  double time_ = 0.0;
  bool playing_ = false;
  QElapsedTimer clock_;
  double clock_start_ = 0.0;  // the replay's time when the clock started
  QTimer* timer_ = nullptr;
  QLabel *label_ = nullptr, *time_label_ = nullptr;
  QPushButton *play_ = nullptr, *close_ = nullptr;
  QSlider* slider_ = nullptr;
};

}  // namespace handlab::gui
