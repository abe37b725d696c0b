// A session's participant view in the OpenXR headset, for `session run --display headset`:
// each step's drawing (studies::ParticipantView) shown there, drawn offscreen with OSMesa; with
// `--tracker openxr`, the hands of the headset's own session drive it, and the time from a hand
// frame to the headset showing it is kept. The
// headset taken off (its session out of focus) pauses the session before its next trial until
// it is back; the runtime gone stops the session (the trial under way is kept as aborted, and
// `--resume` runs it again).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "core/tracking/latest_frames.h"
#include "core/xr/headset_view.h"
#include "studies/session/participant_view.h"
#include "studies/session/session_control.h"

namespace handlab::cli {

// The eyes drawn offscreen (OSMesa), each renderer made on the headset's thread.
xr::HeadsetView::DrawerFactory offscreen_eyes();

class SessionHeadset {
 public:
  // Opens the headset and sets `control`'s trial_started and stepped observers; `say` gets a
  // line, on the headset's thread, when the headset's state changes what the session does. Throws
  // std::runtime_error where no headset can be opened.
  // With `hands`, the headset's own session also tracks the hands, which hands() gives.
  SessionHeadset(studies::SessionControl& control, std::function<void(const std::string&)> say,
                 bool hands = false);
  // The headset's hands, newest first, for a live tracker (null without them).
  std::shared_ptr<tracking::LatestFrames> hands() const { return hands_; }
  ~SessionHeadset();
  // Ends the headset's session; the counts stay.
  void close();
  xr::HeadsetCounts counts() const { return headset_->counts(); }
  std::string error() const { return headset_->error(); }
  std::string runtime_name() const { return headset_->runtime_name(); }

 private:
  void state_changed(const std::string& state);

  studies::SessionControl& control_;
  std::function<void(const std::string&)> say_;  // from the headset's thread
  studies::ParticipantView view_;
  std::shared_ptr<tracking::LatestFrames> hands_;
  std::unique_ptr<xr::HeadsetView> headset_;
  bool paused_by_headset_ = false, was_focused_ = false;
  std::atomic<bool> closing_{false};  // our own end of the headset's session
};

}  // namespace handlab::cli
