// The live display's figures (docs/performance.md, "The live Leap path"): per live frame, the
// time from its arrival to the swap of the first picture of a state simulated from it (other
// trackers: from the step); a frame whose state a newer one replaced before the display took
// it is not counted. Pictures and seconds count the pictures of new steps and the time between
// them (not the pauses between trials).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

namespace handlab::live {
struct LiveFrameStats;
}  // namespace handlab::live

namespace handlab::gui {

struct DisplayStats {
  std::vector<double> latency_ms;
  std::vector<double> pipeline_ms;  // of which until the simulated state was there
  long pictures = 0;
  double seconds = 0;
  long frames_used = 0, frames_superseded = 0;  // live frames a step took, or never took
};

class DisplayLatency {
 public:
  using Clock = std::chrono::steady_clock;

  // A session starts: nothing pending; `live` counts the live tracker's frames (null: another
  // tracker, whose latency runs from the step).
  void start(std::shared_ptr<const live::LiveFrameStats> live);
  // The figures afresh, the session going on (a measurement leaves out its start).
  void reset();
  // The picture of a new step went to the view: its frame arrived at `frame_arrival_ns` (live)
  // and its step was done at `stepped_at`.
  void picture_made(long long frame_arrival_ns, Clock::time_point stepped_at);
  // The view swapped the picture made last.
  void picture_shown();
  const DisplayStats& stats() const { return stats_; }

 private:
  std::shared_ptr<const live::LiveFrameStats> live_;
  DisplayStats stats_;
  long used_before_ = 0, superseded_before_ = 0;  // live counts at the last reset
  // A new step's picture waits for its swap; when its frame arrived (or its step ran), if that
  // frame was not shown before.
  bool picture_waiting_ = false;
  std::optional<Clock::time_point> pending_origin_;
  long long pending_arrival_ns_ = 0, shown_arrival_ns_ = 0;
  Clock::time_point pending_stepped_;
  std::optional<Clock::time_point> last_shown_;
};

}  // namespace handlab::gui
