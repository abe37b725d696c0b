#include "studies/session/trial_driver.h"

#include "core/hand/simulated_hand.h"

namespace handlab::studies {

PipelineTrialDriver::PipelineTrialDriver(TrackerPtr tracker, double rate_hz, WorldKind world,
                                         int sim_threads)
    : tracker_(std::move(tracker)),
      rate_hz_(rate_hz),
      rigs_(tracker_, world, rate_hz, sim_threads) {}

// For the first condition's simulated hand: the runner rescales for conditions of other lengths.
retarget::Calibration PipelineTrialDriver::calibrate(const Protocol& protocol,
                                                     const store::Participant& participant) {
  const hand::Skeleton first =
      hand::build_simulated_hand(protocol.conditions().front().simulated_hand);
  return tracker_->calibrate(protocol, participant, first, control_);
}

TrialRun PipelineTrialDriver::run(const TrialSetup& setup, const FrameSink& sink) {
  TrialRig rig = rigs_.build(setup);
  return run_trial(rig, sink, {rate_hz_, real_time_, control_});
}

}  // namespace handlab::studies
