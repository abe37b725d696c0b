// OpenXR's hand tracking as a live tracker: a session of its own with no graphics
// (XR_MND_headless), a hand tracker for each hand (XR_EXT_hand_tracking), and on a thread of
// its own the joints of both hands located in the LOCAL space 120 times a second at the
// runtime's time of CLOCK_MONOTONIC (XR_KHR_convert_timespec_time), each read as a tracked
// frame (core/tracking/openxr_hand.h).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "core/tracking/frame_source.h"

namespace handlab::xr {

class OpenXrHandSource : public tracking::LiveFrameSource {
 public:
  // The runtime's hands, once its session runs; nullptr with `error` saying why where the
  // loader, the runtime, the headless extension, the hand tracking or the session is missing.
  static std::unique_ptr<OpenXrHandSource> open(
      std::string& error,
      std::chrono::milliseconds start_timeout = std::chrono::milliseconds(5000));
  ~OpenXrHandSource() override;

  // The newest frame since the last call, nullopt when none came (never blocks).
  std::optional<tracking::TrackedFrame> next() override;
  bool wait_for_frame(std::chrono::steady_clock::time_point deadline) override;

  // The session ended (the runtime stopped it or was lost): no more frames come.
  bool ended() const override;
  std::string runtime_name() const;

  struct Session;  // the OpenXR handles and the loop (openxr_hand_source.cpp)

 private:
  explicit OpenXrHandSource(std::unique_ptr<Session> session);
  std::unique_ptr<Session> session_;
};

// A view of a shared source for one user at a time (a session's calibration, then each trial):
// frames that came before the view was made are not its own.
std::unique_ptr<tracking::LiveFrameSource> view_of(
    std::shared_ptr<tracking::LiveFrameSource> source);

}  // namespace handlab::xr
