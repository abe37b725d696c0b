#include "studies/session/session_headset.h"

#include <limits>
#include <stdexcept>

#include "core/render/scene_drawing.h"
#include "core/task/scene_layout.h"

namespace handlab::studies {

SessionHeadset::SessionHeadset(SessionControl& control, const task::SceneLayout& scene,
                               xr::HeadsetView::DrawerFactory eyes,
                               std::function<void(const std::string&)> say, bool hands)
    : control_(control), say_(std::move(say)), layout_(scene) {
  xr::OpenXrDisplay::HandSink sink;
  if (hands) {
    hands_ = std::make_shared<tracking::LatestFrames>();
    sink = [frames = hands_](tracking::TrackedFrame f) { frames->publish(std::move(f)); };
  }
  std::string error;
  headset_ = xr::HeadsetView::open(
      error, std::move(eyes), [this](const std::string& state) { state_changed(state); }, 0,
      std::move(sink));
  if (!headset_) throw std::runtime_error(error + " (docs/hmd.md)");
  headset_->start();  // its frames (and hands) from now, the calibration's too
}

SessionHeadset::~SessionHeadset() {
  close();
}

void SessionHeadset::trial_started(const TrialSetup& setup) {
  view_.start_trial(setup);
  const std::lock_guard lock(mutex_);
  layout_ = view_.layout();
  scene_.reset();  // a panel set before the trial's first step stands on its scene
}

void SessionHeadset::stepped(const TrialStep& step) {
  if (closing_) return;
  render::DrawList scene = view_.draw(step);
  const std::lock_guard lock(mutex_);
  scene_ = std::move(scene);
  cube_ = step.frame ? step.frame->cube_position : Eigen::Vector3f::Zero();
  // Made from a hand frame of the headset's (a step with no frame yet has no time of one).
  const bool from_hands = hands_ && step.frame && !step.frame->tracked.hands.empty();
  show_locked(from_hands ? step.frame->tracked.timestamp
                         : std::numeric_limits<double>::quiet_NaN());
}

void SessionHeadset::set_panel(std::shared_ptr<const render::Image> picture) {
  if (closing_) return;
  const std::lock_guard lock(mutex_);
  panel_ = std::move(picture);
  if (!scene_) {  // before the trial's first step: the scene as it starts
    scene_ = render::draw_task_scene(layout_, task::cube_start_pose(layout_));
    cube_ = task::cube_start_pose(layout_).translation().cast<float>();
  }
  show_locked(std::numeric_limits<double>::quiet_NaN());  // no hand frame newly shown
}

void SessionHeadset::show_locked(double hand_time) {
  render::DrawList shown = *scene_;
  render::draw_panel(shown, layout_, panel_);
  headset_->show(std::move(shown), cube_, hand_time);
}

void SessionHeadset::close() {
  closing_ = true;
  if (hands_) hands_->finish();
  if (headset_) headset_->close();
}

// On the headset's thread.
void SessionHeadset::state_changed(const std::string& state) {
  if (closing_) return;
  if (state == "focused") {
    was_focused_ = true;
    if (paused_by_headset_) {
      paused_by_headset_ = false;
      control_.set_paused(false);
      say_("the headset is in focus again: the session goes on");
    }
  } else if (state == "exiting" || state == "loss pending" || state == "failed") {
    if (hands_) hands_->finish();
    if (!control_.stop_requested()) {
      control_.request_stop();
      say_((state == "failed" ? "the headset failed (" + headset_->error() + ")"
                              : "the headset's runtime ended its session (" + state + ")") +
           ": the session stops; the trial under way is kept as aborted and runs again when "
           "the session resumes");
    }
  } else if (was_focused_ && !paused_by_headset_ && state != "stopping") {
    paused_by_headset_ = true;
    control_.set_paused(true);
    say_("the headset is out of focus (" + state +
         ": taken off?): the session pauses before its next trial");
  }
}

}  // namespace handlab::studies
