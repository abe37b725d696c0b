// A tracker that never looks at the display (the scripted participant, a recording) as a
// trial's frame source: its frames in order until it ends.
#pragma once

#include <memory>

#include "core/tracking/frame_source.h"
#include "studies/session/trial_frame_source.h"

namespace handlab::studies {

class OpenLoopSource : public TrialFrameSource {
 public:
  explicit OpenLoopSource(std::unique_ptr<tracking::FrameSource> frames)
      : frames_(std::move(frames)) {}
  std::optional<tracking::TrackedFrame> next(const Observation&) override {
    if (ended_) return std::nullopt;
    std::optional<tracking::TrackedFrame> frame = frames_->next();
    ended_ = !frame;
    return frame;
  }
  bool ended() const override { return ended_; }

 private:
  std::unique_ptr<tracking::FrameSource> frames_;
  bool ended_ = false;
};

}  // namespace handlab::studies
