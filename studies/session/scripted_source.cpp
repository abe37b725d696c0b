// The built-in scripted participant (scripted_tracker.h) as a session's tracker.
#include <memory>

#include "core/util/portable_random.h"
#include "studies/session/open_loop_source.h"
#include "studies/session/scripted_tracker.h"
#include "studies/session/tracker.h"

namespace handlab::studies {
namespace {

double tip_radius(const hand::Skeleton& s) {
  const int tip = s.marker_index("index_tip");
  return s.bones[std::size_t(s.markers[std::size_t(tip)].bone)].radius;
}

class Scripted : public Tracker {
 public:
  std::string name() const override { return "scripted"; }

  retarget::Calibration calibrate(const Protocol& protocol, const store::Participant& participant,
                                  const hand::Skeleton& first_hand,
                                  SessionControl* control) const override {
    return scripted_calibration(protocol.scene, participant.hand_length, first_hand, control);
  }

  std::unique_ptr<TrialFrameSource> open(const TrialSetup& setup, const hand::Skeleton& simulated,
                                         double rate_hz, TrialCache&) const override {
    ScriptedMotionSettings settings;
    settings.hand_length = setup.participant.hand_length;
    settings.scale = setup.calibration.scale;
    settings.simulated_tip_radius = tip_radius(simulated);
    settings.layout = trial_layout(setup);
    settings.rate_hz = rate_hz;
    // A person is not a metronome: each trial's tempo varies by up to 15 %, drawn from the
    // participant and the trial so that a session replays identically.
    util::PortableRandom random(
        util::fnv1a64(setup.participant.id) ^
        (0x9E3779B97F4A7C15ull * std::uint64_t(setup.planned.position + 1)));
    settings.tempo = 0.85 + 0.3 * random.uniform();
    return std::make_unique<OpenLoopSource>(std::make_unique<ScriptedTracker>(settings));
  }
};

}  // namespace

TrackerPtr scripted_tracker() {
  return std::make_shared<const Scripted>();
}

}  // namespace handlab::studies
