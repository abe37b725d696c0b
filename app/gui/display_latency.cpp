#include "app/gui/display_latency.h"

#include "app/live/live_frames.h"

namespace handlab::gui {

void DisplayLatency::start(std::shared_ptr<const live::LiveFrameStats> live) {
  live_ = std::move(live);
  reset();
  pending_origin_.reset();
  picture_waiting_ = false;
  pending_arrival_ns_ = shown_arrival_ns_ = 0;
}

void DisplayLatency::reset() {
  stats_ = {};
  last_shown_.reset();
  used_before_ = live_ ? live_->used.load() : 0;
  superseded_before_ = live_ ? live_->superseded.load() : 0;
}

void DisplayLatency::picture_made(long long frame_arrival_ns, Clock::time_point stepped_at) {
  picture_waiting_ = true;
  // A live frame's latency counts once, with the first picture of a state simulated from it.
  if (live_) {
    stats_.frames_used = live_->used - used_before_;
    stats_.frames_superseded = live_->superseded - superseded_before_;
    if (frame_arrival_ns == 0 || frame_arrival_ns == shown_arrival_ns_) return;
  }
  pending_origin_ = live_ ? Clock::time_point(Clock::duration(frame_arrival_ns)) : stepped_at;
  pending_arrival_ns_ = frame_arrival_ns;
  pending_stepped_ = stepped_at;
}

void DisplayLatency::picture_shown() {
  if (!picture_waiting_) return;
  picture_waiting_ = false;
  const auto now = Clock::now();
  if (pending_origin_) {
    auto ms = [](auto duration) {
      return std::chrono::duration<double, std::milli>(duration).count();
    };
    stats_.latency_ms.push_back(ms(now - *pending_origin_));
    stats_.pipeline_ms.push_back(ms(pending_stepped_ - *pending_origin_));
    pending_origin_.reset();
    shown_arrival_ns_ = pending_arrival_ns_;
  }
  ++stats_.pictures;
  // The display rate counts the time between pictures, not the pauses between trials.
  if (last_shown_ && now - *last_shown_ < std::chrono::milliseconds(250))
    stats_.seconds += std::chrono::duration<double>(now - *last_shown_).count();
  last_shown_ = now;
}

}  // namespace handlab::gui
