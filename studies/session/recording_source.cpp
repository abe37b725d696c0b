// A recording replayed at the simulation rate for every trial, as a session's tracker.
#include <algorithm>
#include <memory>
#include <stdexcept>

#include "core/tracking/recording_io.h"
#include "studies/session/open_loop_source.h"
#include "studies/session/tracker.h"

namespace handlab::studies {
namespace {

using tracking::Side;

class Recording : public Tracker {
 public:
  explicit Recording(std::string path)
      : path_(std::move(path)), frames_(tracking::read_recording(path_).frames) {
    const bool any = std::any_of(frames_.begin(), frames_.end(),
                                 [](const auto& f) { return f.hand(Side::kRight) != nullptr; });
    if (!any) throw std::runtime_error(path_ + " has no right hand to drive the trials");
  }

  std::string name() const override { return path_; }

  // Its own open-palm frames (or the length ratio without any), and the recording's median
  // palm placed 12 cm above zone A.
  retarget::Calibration calibrate(const Protocol& protocol, const store::Participant&,
                                  const hand::Skeleton& first_hand,
                                  SessionControl* control) const override {
    retarget::Calibration c;
    auto fitter = tracking::TrackedHandFitter::for_recording(frames_, Side::kRight);
    if (auto open = retarget::calibrate_open_palm(frames_, Side::kRight, first_hand, *fitter))
      c = *open;
    else
      c.scale = protocol.conditions().front().simulated_hand_length /
                tracking::estimate_hand_length(frames_, Side::kRight).value();
    std::vector<double> axis[3];
    for (const auto& f : frames_)
      if (const auto* h = f.hand(Side::kRight))
        for (int i = 0; i < 3; ++i) axis[i].push_back(h->palm_position[i]);
    Eigen::Vector3d median;
    for (int i = 0; i < 3; ++i) {
      std::nth_element(axis[i].begin(), axis[i].begin() + long(axis[i].size() / 2), axis[i].end());
      median[i] = axis[i][axis[i].size() / 2];
    }
    c.tracker_to_scene =
        Eigen::Translation3d(protocol.scene.zone_a + Eigen::Vector3d(0, 0.12, 0) - median);
    report_calibration(control, c, frames_.front());
    return c;
  }

  // The recorded hand's own skeleton.
  std::optional<tracking::TrackedHandFitter> fitter(const store::Participant&) const override {
    return tracking::TrackedHandFitter::for_recording(frames_, Side::kRight);
  }

  std::unique_ptr<TrialFrameSource> open(const TrialSetup&, const hand::Skeleton&, double rate_hz,
                                         TrialCache&) const override {
    tracking::ReplayOptions options;
    options.pace = tracking::ReplayPace::kResampled;
    options.rate_hz = rate_hz;
    return std::make_unique<OpenLoopSource>(
        std::make_unique<tracking::RecordingReplay>(frames_, options));
  }

 private:
  std::string path_;
  std::vector<tracking::TrackedFrame> frames_;
};

}  // namespace

TrackerPtr recording_tracker(const std::string& path) {
  return std::make_shared<const Recording>(path);
}

}  // namespace handlab::studies
