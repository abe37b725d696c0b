// A stored trial played back from its frame log (studies/session/trial_replay.h): a session
// run headless on the grasp proxy, its trials read back with their condition's scene, any
// moment found by time, a redone trial's attempts told apart, and what cannot be replayed
// refused with the reason.
#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_control.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"
#include "studies/session/trial_replay.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

using test::kStudy;

bool within_zone(const Eigen::Vector3f& p, const Eigen::Vector3d& zone, double size) {
  return std::abs(p.x() - zone.x()) <= size / 2 && std::abs(p.z() - zone.z()) <= size / 2;
}

TEST(TrialReplay, PlaysBackWhatTheSessionLogged) {
  const Protocol protocol = read_protocol(kStudy);
  const std::string path = test::fresh_path("replay.db");
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  enrol_participant(db, test::participant("P01"));
  // Four trials by the scripted participant, stopped in the fifth.
  PipelineTrialDriver driver(scripted_tracker());
  SessionRunner runner(db, driver, fixed_responder());
  SessionControl control;
  int started = 0;
  control.trial_started = [&](const TrialSetup&, int) { ++started; };
  control.stepped = [&](const TrialStep&) {
    if (started == 5) control.request_stop();
  };
  runner.attach(&control);
  runner.run("P01", "scripted", false);

  const auto plan = db.plan("P01");
  const auto conditions = protocol.conditions();
  const auto trials = db.trials("P01");
  ASSERT_GE(trials.size(), 4u);
  for (int position = 0; position < 4; ++position) {
    const TrialReplay replay = load_trial_replay(db, "P01", position);
    const Condition& condition = conditions.at(std::size_t(plan[std::size_t(position)].condition));
    EXPECT_EQ(replay.condition, condition.label);
    EXPECT_EQ(replay.layout.cube_size, condition.cube_size);
    EXPECT_EQ(replay.simulated_hand.length, condition.simulated_hand.length);
    EXPECT_EQ(replay.attempt, 1);
    const store::TrialRow& row = trials[std::size_t(position)];
    ASSERT_EQ(row.position, position);
    EXPECT_EQ(replay.status, row.status);
    EXPECT_EQ(int(replay.frames.size()), row.frames);
    // The frames in order, 120 a second; the cube starts at A and, in a completed trial,
    // ends at B.
    for (std::size_t k = 1; k < replay.frames.size(); ++k)
      ASSERT_NEAR(replay.frames[k].time - replay.frames[k - 1].time, 1.0 / 120.0, 1e-9);
    EXPECT_TRUE(within_zone(replay.frames.front().cube_position, replay.layout.zone_a,
                            replay.layout.zone_size));
    if (row.status == store::TrialStatus::kCompleted) {
      EXPECT_TRUE(within_zone(replay.frames.back().cube_position, replay.layout.zone_b,
                              replay.layout.zone_size));
    }
    // Any moment shows the last frame logged at or before it.
    const double mid = replay.duration() / 2;
    const store::FrameRecord& at = replay.frame_at(mid);
    EXPECT_LE(at.time, mid);
    EXPECT_GT(at.time, mid - 1.0 / 120.0);
    EXPECT_EQ(&replay.frame_at(-1.0), &replay.frames.front());
    EXPECT_EQ(&replay.frame_at(1e9), &replay.frames.back());
    EXPECT_EQ(&replay.frame_at(replay.frames[7].time), &replay.frames[7]);
  }

  // The stopped fifth trial has frames of its own (aborted); redone, trial 2 keeps the
  // frames of its attempt 1, which stays the latest with frames until it runs again.
  const TrialReplay aborted = load_trial_replay(db, "P01", 4);
  EXPECT_EQ(aborted.status, store::TrialStatus::kAborted);
  EXPECT_FALSE(aborted.frames.empty());
  db.redo_trial("P01", 1, "looked away");
  const TrialReplay redone = load_trial_replay(db, "P01", 1);
  EXPECT_EQ(redone.attempt, 1);
  EXPECT_EQ(redone.status, store::TrialStatus::kRedone);

  // What cannot be replayed says why.
  auto refusal = [&](const std::string& id, int position, int attempt) {
    try {
      load_trial_replay(db, id, position, attempt);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(refusal("P09", 0, 0), "no participant 'P09' in this study");
  EXPECT_EQ(refusal("P01", 20, 0), "P01 has no trial 21 (the schedule has 20)");
  EXPECT_EQ(refusal("P01", 0, 2), "trial 1 of P01 has no attempt 2");
  EXPECT_NE(refusal("P01", 10, 0).find("trial 11 of P01 has no logged frames"), std::string::npos);
}

}  // namespace
}  // namespace handlab::studies
