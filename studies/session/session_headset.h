// A session's participant view in the OpenXR headset (`session run --display headset`, the
// app's headset display): each step's drawing (ParticipantView) shown there by the front
// end's eye drawer; with hands, the headset's own session tracks them for a live tracker
// (openxr_tracker), and the time from a hand frame to the headset showing it is kept.
// The headset taken off (its session out of focus) pauses the session before its next trial
// until it is back; the runtime gone stops the session (the trial under way is kept as
// aborted, and a resumed session runs it again).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/tracking/latest_frames.h"
#include "core/xr/headset_view.h"
#include "studies/session/participant_view.h"
#include "studies/session/session_control.h"

namespace handlab::studies {

class SessionHeadset {
 public:
  // Opens the headset and starts its frame loop; `say` gets a line, on the headset's thread,
  // when the headset's state changes what the session does (its drawing failing stops the
  // session as its runtime ending does). Throws std::runtime_error where no headset can be
  // opened.
  // `scene`: the study's, shown until a trial starts (the calibration's instruction stands
  // on it).
  SessionHeadset(SessionControl& control, const task::SceneLayout& scene,
                 xr::HeadsetView::DrawerFactory eyes, std::function<void(const std::string&)> say,
                 bool hands = false);
  ~SessionHeadset();
  // The front end's observers call these on the session thread.
  void trial_started(const TrialSetup& setup);
  void stepped(const TrialStep& step);
  // From any thread: a picture on a panel before the participant (the instruction, a
  // questionnaire; render::draw_panel), shown at once and with every step after it; null
  // takes the panel away.
  void set_panel(std::shared_ptr<const render::Image> picture);
  // Ends the headset's session; the counts stay. Call after the session's last step.
  void close();

  // The headset's hands, newest first, for a live tracker (null without them).
  std::shared_ptr<tracking::LatestFrames> hands() const { return hands_; }
  xr::HeadsetCounts counts() const { return headset_->counts(); }
  std::string error() const { return headset_->error(); }
  std::string runtime_name() const { return headset_->runtime_name(); }
  // The last frame shown, each eye as read back from the headset.
  xr::DisplayFrame last_frame() const { return headset_->last_frame(); }

 private:
  void state_changed(const std::string& state);
  // With mutex_ held: the newest scene and the panel to the headset.
  void show_locked(double hand_time);

  SessionControl& control_;
  std::function<void(const std::string&)> say_;  // from the headset's thread
  ParticipantView view_;
  std::mutex mutex_;                       // what the GUI's set_panel shares
  task::SceneLayout layout_;               // the trial's
  std::optional<render::DrawList> scene_;  // the newest step's, without the panel
  Eigen::Vector3f cube_ = Eigen::Vector3f::Zero();
  std::shared_ptr<const render::Image> panel_;
  std::shared_ptr<tracking::LatestFrames> hands_;
  std::unique_ptr<xr::HeadsetView> headset_;
  bool paused_by_headset_ = false, was_focused_ = false;
  std::atomic<bool> closing_{false};  // our own end of the headset's session
};

}  // namespace handlab::studies
