// A live tracker (app/live: the Leap over its WebSocket) as a session's tracker: a person
// calibrates with an open palm, and each step takes the newest frame as soon as it arrives.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "studies/session/open_palm_calibration.h"
#include "studies/session/session_control.h"
#include "studies/session/tracker.h"

namespace handlab::studies {
namespace {

class LiveSource : public TrialFrameSource {
 public:
  explicit LiveSource(std::unique_ptr<tracking::LiveFrameSource> frames)
      : frames_(std::move(frames)) {}
  // The newest frame, or the last one again while none has come since.
  std::optional<tracking::TrackedFrame> next(const Observation&) override {
    if (auto fresh = frames_->next()) held_ = std::move(fresh);
    return held_;
  }
  bool live() const override { return true; }
  bool ended() const override { return frames_->ended(); }
  // A frame is used as soon as it arrives, the step taken up to one step early rather than
  // the frame left waiting for its tick: the simulation keeps within a step of the clock, and
  // a frame's latency is the step's, not the step's plus the tick's.
  void wait_for_step(Clock::time_point due, Clock::duration period) override {
    std::this_thread::sleep_until(due - period);
    frames_->wait_for_frame(due);
  }

 private:
  std::unique_ptr<tracking::LiveFrameSource> frames_;
  std::optional<tracking::TrackedFrame> held_;
};

class Live : public Tracker {
 public:
  Live(std::string name, LiveOpener open) : name_(std::move(name)), open_(std::move(open)) {}

  std::string name() const override { return name_; }

  // A person: the open palm held still, frame by frame, as long as it takes.
  retarget::Calibration calibrate(const Protocol& protocol, const store::Participant& participant,
                                  const hand::Skeleton& first_hand,
                                  SessionControl* control) const override {
    OpenPalmCalibration step(protocol.scene, first_hand, participant.hand_length);
    const std::unique_ptr<tracking::LiveFrameSource> source = open_();
    while (!step.done()) {
      if (control && control->stop_requested()) throw SessionStopped();
      if (source->ended()) throw std::runtime_error("the tracker stopped before the calibration was done");
      // Each frame as it comes; a stop is seen within a tenth of a second without frames.
      source->wait_for_frame(std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
      if (const auto frame = source->next()) {
        step.feed(*frame);
        if (control && control->calibration) control->calibration(step.status());
      }
    }
    return *step.status().result;
  }

  std::unique_ptr<TrialFrameSource> open(const TrialSetup&, const hand::Skeleton&, double,
                                         TrialCache&) const override {
    return std::make_unique<LiveSource>(open_());
  }

 private:
  std::string name_;
  LiveOpener open_;
};

}  // namespace

TrackerPtr live_tracker(std::string name, LiveOpener open) {
  return std::make_shared<const Live>(std::move(name), std::move(open));
}

}  // namespace handlab::studies
