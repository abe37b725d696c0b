// Where tracked frames come from, behind one interface: a recording replayed (as fast as
// possible, in real time, or resampled to a fixed rate) or, in app/, the live Leap stream.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <vector>

#include "core/tracking/tracked_frame.h"

namespace handlab::tracking {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame; nullopt once the source has ended. Live sources may block.
  virtual std::optional<TrackedFrame> next() = 0;
};

// A live tracker's frames as a session reads them (the Leap over its WebSocket, in app/):
// next() never blocks and gives the newest frame that arrived since the last call, nullopt
// when none came; wait_for_frame() lets a step follow a frame as soon as it arrives.
class LiveFrameSource : public FrameSource {
 public:
  // Returns once a frame not yet taken by next() is there (true) or at `deadline` (false).
  virtual bool wait_for_frame(std::chrono::steady_clock::time_point deadline) = 0;
  // No frame will come any more (the tracker's runtime ended its session).
  virtual bool ended() const { return false; }
};

enum class ReplayPace { kAsFastAsPossible, kRealTime, kResampled };

struct ReplayOptions {
  ReplayPace pace = ReplayPace::kAsFastAsPossible;
  double rate_hz = 90.0;  // for kResampled
  // How real-time replay waits (seconds); defaults to sleeping this thread. Tests count.
  std::function<void(double)> sleep;
};

class RecordingReplay : public FrameSource {
 public:
  RecordingReplay(std::vector<TrackedFrame> frames, ReplayOptions options = {});
  std::optional<TrackedFrame> next() override;

 private:
  std::vector<TrackedFrame> frames_;
  ReplayOptions options_;
  std::size_t index_ = 0;
  double time_ = 0.0;  // resampling clock (s)
};

// The frame at time t between a and b (a.timestamp <= t <= b.timestamp): positions and
// scalars interpolated linearly, orientations (palm frame, bone bases) by slerp. Hands are
// matched by id; one seen in only one of the frames comes from the nearer frame.
TrackedFrame interpolate(const TrackedFrame& a, const TrackedFrame& b, double t);

}  // namespace handlab::tracking
