// The trial's frame-source contract (studies/session/trial_frame_source.h) as any tracker
// plugs into it: a tracker of the test's own, not one of handlab's kinds, drives the pipeline.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/task/cube_task.h"
#include "studies/session/trial_driver.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

// The scripted participant's frames, up to `frames` of them, noting what it was shown.
class WatchingSource : public TrialFrameSource {
 public:
  WatchingSource(std::unique_ptr<TrialFrameSource> inner, long frames,
                 std::vector<Observation>& seen)
      : inner_(std::move(inner)), frames_(frames), seen_(seen) {}
  std::optional<tracking::TrackedFrame> next(const Observation& shown) override {
    seen_.push_back(shown);
    if (long(seen_.size()) > frames_) ended_ = true;
    return ended_ ? std::nullopt : inner_->next(shown);
  }
  bool ended() const override { return ended_; }

 private:
  std::unique_ptr<TrialFrameSource> inner_;
  long frames_;
  std::vector<Observation>& seen_;
  bool ended_ = false;
};

class WatchingTracker : public Tracker {
 public:
  WatchingTracker(long frames, std::vector<Observation>& seen) : frames_(frames), seen_(seen) {}
  std::string name() const override { return "watching"; }
  retarget::Calibration calibrate(const Protocol& protocol, const store::Participant& participant,
                                  const hand::Skeleton& first_hand,
                                  SessionControl* control) const override {
    return scripted_->calibrate(protocol, participant, first_hand, control);
  }
  std::unique_ptr<TrialFrameSource> open(const TrialSetup& setup, const hand::Skeleton& simulated,
                                         double rate_hz, TrialCache& cache) const override {
    return std::make_unique<WatchingSource>(scripted_->open(setup, simulated, rate_hz, cache),
                                            frames_, seen_);
  }

 private:
  TrackerPtr scripted_ = scripted_tracker();
  long frames_;
  std::vector<Observation>& seen_;
};

struct Trial {
  TrialRun run;
  std::vector<Observation> seen;
  std::vector<store::FrameRecord> records;
};

Trial run_watched(long frames) {
  static const Protocol protocol = read_protocol(test::kStudy);
  Trial trial;
  PipelineTrialDriver driver(std::make_shared<const WatchingTracker>(frames, trial.seen));
  TrialSetup setup;
  setup.protocol = &protocol;
  setup.condition = protocol.conditions().front();
  setup.participant = test::participant("S", 0.18);
  setup.calibration = driver.calibrate(protocol, setup.participant);
  trial.run = driver.run(setup, [&](const store::FrameRecord& f) { trial.records.push_back(f); });
  return trial;
}

// Each step's source sees the display after the step before (at 0 before the first): the
// time and the cube where the last record left them.
TEST(TrialLoop, TheSourceSeesTheDisplayAfterTheLastStep) {
  const Trial t = run_watched(100000);
  EXPECT_TRUE(t.run.success);
  ASSERT_EQ(t.seen.size(), t.records.size());
  EXPECT_EQ(t.seen[0].time, 0.0);
  for (std::size_t k = 1; k < t.seen.size(); ++k) {
    ASSERT_EQ(t.seen[k].time, t.records[k - 1].time) << k;
    ASSERT_EQ(t.seen[k].cube_position.cast<float>(), t.records[k - 1].cube_position) << k;
  }
}

// A source that ends while the cube waits untouched on the floor: nothing can happen any more,
// and the trial times out at once rather than stepping through its time limit, its end logged
// as one more frame of the same scene at the limit, in the phase it ended in.
TEST(TrialLoop, ASourceThatEndsBeforeTheGraspTimesTheTrialOut) {
  const Trial t = run_watched(30);
  EXPECT_FALSE(t.run.success);
  EXPECT_EQ(t.run.grasps, 0);
  EXPECT_EQ(t.run.frames, 32) << "the step that found the source ended, then the end";
  ASSERT_EQ(t.records.size(), 32u);
  const store::FrameRecord &found = t.records[30], &end = t.records[31];
  EXPECT_EQ(task::TaskPhase(found.task_phase), task::TaskPhase::kStarted);
  EXPECT_EQ(task::TaskPhase(end.task_phase), task::TaskPhase::kFailed);
  EXPECT_GT(end.time, found.time + 1.0) << "at the trial's time limit";
  EXPECT_EQ(end.cube_position, found.cube_position);
  ASSERT_FALSE(t.run.events.empty());
  EXPECT_EQ(t.run.events.back().second, "timeout");
}

}  // namespace
}  // namespace handlab::studies
