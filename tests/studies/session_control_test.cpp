// A front end steering the session runner (studies/session/session_control.h): pausing
// before the next trial, stopping a trial under way (kept as aborted, run again on resume),
// the experimenter's redo and skip applied between trials, the observers; and the open-palm
// calibration step on real Leap frames.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/render/frame_drawing.h"
#include "core/store/study_store.h"
#include "core/tracking/recording_io.h"
#include "studies/session/open_palm_calibration.h"
#include "studies/session/session_control.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

using test::kStudy;

std::string enrolled_study(const std::string& name, const Protocol& protocol) {
  const std::string path = test::fresh_path(name);
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  db.add_participant(test::participant("P01"), planned_rows(protocol, "P01", 0));
  return path;
}

// A skip between sessions is recorded in a session of its own; a refused one (a trial that
// does not exist) leaves no session open that would look interrupted.
TEST(SessionControl, SkipBetweenSessionsKeepsItsOwnSessionAndNoneOpenWhenRefused) {
  const Protocol protocol = read_protocol(kStudy);
  store::StudyStore db(enrolled_study("control_skip.db", protocol));
  skip_trial_between_sessions(db, "P01", 5, "participant tired");
  EXPECT_THROW(skip_trial_between_sessions(db, "P01", 99, "no such trial"), std::exception);
  EXPECT_FALSE(db.has_running_session("P01"));
  const auto trials = db.trials("P01");
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_EQ(trials[0].position, 5);
  EXPECT_EQ(trials[0].status, store::TrialStatus::kSkipped);
  EXPECT_EQ(trials[0].reason, "participant tired");
  std::vector<std::string> sessions;
  store::Statement s = db.database().prepare("SELECT tracker, status FROM session ORDER BY id");
  while (s.step()) sessions.push_back(s.column_text(0) + " " + s.column_text(1));
  EXPECT_EQ(sessions, (std::vector<std::string>{"experimenter stopped", "experimenter stopped"}));
}

// Stop during the third trial, then resume: the stopped attempt is kept as aborted with its
// reason, the session is recorded as stopped, and the resumed session runs that trial again.
TEST(SessionControl, StopAbortsTheRunningTrialWhichRunsAgainOnResume) {
  const Protocol protocol = read_protocol(kStudy);
  const std::string path = enrolled_study("control_stop.db", protocol);
  store::StudyStore db(path);
  PipelineTrialDriver driver(scripted_tracker());
  SessionRunner runner(db, driver, fixed_responder());
  SessionControl control;
  int started = 0, ended = 0;
  long steps = 0;
  control.trial_started = [&](const TrialSetup&, int planned) {
    EXPECT_EQ(planned, 20);
    ++started;
  };
  control.trial_ended = [&](const TrialSetup&, const TrialRun&) { ++ended; };
  control.stepped = [&](const TrialStep& step) {
    ASSERT_NE(step.frame, nullptr);
    EXPECT_DOUBLE_EQ(step.frame->time, step.time);
    if (started == 3 && step.time > 1.0) control.request_stop();
    ++steps;
  };
  bool calibrated = false;
  control.calibration = [&](const CalibrationStatus& s) {
    calibrated = s.state == CalibrationStatus::State::kDone && s.result && s.result->scale > 1;
  };
  runner.attach(&control);
  const SessionReport report = runner.run("P01", "scripted", false);
  EXPECT_TRUE(calibrated);
  EXPECT_TRUE(report.stopped);
  EXPECT_FALSE(report.schedule_complete);
  EXPECT_EQ(report.trials_run, 2);
  EXPECT_EQ(started, 3);
  EXPECT_EQ(ended, 3);
  EXPECT_GT(steps, 120);
  auto trials = db.trials("P01");
  ASSERT_EQ(trials.size(), 3u);
  EXPECT_EQ(trials[2].status, store::TrialStatus::kAborted);
  EXPECT_EQ(trials[2].reason, "stopped by the experimenter");
  EXPECT_EQ(db.next_trial("P01")->position, 2);
  {
    store::Statement s = db.database().prepare("SELECT status FROM session");
    ASSERT_TRUE(s.step());
    EXPECT_EQ(s.column_text(0), "stopped");
  }

  // A fresh control (the stop is spent), resumed: trial 3 runs again, attempt 2.
  SessionControl again;
  again.stepped = [&](const TrialStep& step) {
    if (step.time > 0.5) again.request_stop();
  };
  runner.attach(&again);
  EXPECT_TRUE(runner.run("P01", "scripted", true).stopped);
  trials = db.trials("P01");
  ASSERT_EQ(trials.size(), 4u);
  EXPECT_EQ(trials[3].position, 2);
  EXPECT_EQ(trials[3].attempt, 2);
  EXPECT_EQ(trials[3].status, store::TrialStatus::kAborted);
}

// What a front end draws of a step on the soft hand: the flesh and its nodes after the step
// (the frame log keeps only the bones), from which the skin is drawn around the bones as they
// move; on the grasp proxy there is no flesh, and the bones are drawn.
TEST(SessionControl, OnTheSoftHandEachStepHasTheFleshTheSkinIsDrawnFrom) {
  const Protocol protocol = read_protocol(kStudy);
  for (const WorldKind world : {WorldKind::kSoftHand, WorldKind::kGraspProxy}) {
    const bool soft = world == WorldKind::kSoftHand;
    store::StudyStore db(enrolled_study(soft ? "control_soft.db" : "control_proxy.db", protocol));
    PipelineTrialDriver driver(scripted_tracker(), 120.0, world, 1);
    SessionRunner runner(db, driver, fixed_responder());
    SessionControl control;
    long steps = 0, with_flesh = 0, skins_checked = 0;
    std::vector<Eigen::Vector3d> first_nodes;
    double moved = 0.0;  // the largest node displacement since the first step with flesh
    control.stepped = [&](const TrialStep& step) {
      ++steps;
      if (step.time > 1.5) control.request_stop();
      EXPECT_EQ(step.flesh == nullptr, step.flesh_nodes == nullptr);
      if (!step.flesh) return;
      ++with_flesh;
      const hand::HandFlesh& flesh = *step.flesh;
      ASSERT_EQ(step.flesh_nodes->size(), flesh.tets.nodes.size());
      if (first_nodes.empty()) first_nodes = *step.flesh_nodes;
      for (std::size_t n = 0; n < first_nodes.size(); ++n)
        moved = std::max(moved, ((*step.flesh_nodes)[n] - first_nodes[n]).norm());
      if (steps % 30 != 0) return;
      // The skin drawn from them wraps the bones of the same step: its box holds every bone's
      // origin, and it is a hand's size.
      const render::DrawList list = render::draw_soft_hand_frame(
          protocol.scene, flesh.render, flesh.tets, *step.flesh_nodes, *step.frame);
      const auto skin = std::find_if(list.items.begin(), list.items.end(),
                                     [](const render::DrawItem& item) { return item.dynamic; });
      ASSERT_NE(skin, list.items.end());
      ASSERT_EQ(skin->mesh->positions.size(), flesh.render.tet.size());
      ASSERT_EQ(skin->mesh->indices.size(), 3 * flesh.render.triangles.size());
      Eigen::AlignedBox3f box;
      for (const Eigen::Vector3f& p : skin->mesh->positions) box.extend(p);
      ASSERT_FALSE(step.frame->bone_positions.empty());
      for (const Eigen::Vector3f& bone : step.frame->bone_positions)
        EXPECT_TRUE(box.contains(bone)) << "a bone outside the skin at " << step.time << " s";
      EXPECT_GT(box.sizes().maxCoeff(), 0.12f);
      EXPECT_LT(box.sizes().maxCoeff(), 0.30f);
      ++skins_checked;
    };
    runner.attach(&control);
    EXPECT_TRUE(runner.run("P01", "scripted", false).stopped);
    EXPECT_GT(steps, 150);
    if (soft) {
      EXPECT_GT(with_flesh, steps - 5) << "the flesh from the hand's first step on";
      EXPECT_GT(skins_checked, 4);
      EXPECT_GT(moved, 0.02) << "the flesh moves with the hand";
    } else {
      EXPECT_EQ(with_flesh, 0);
    }
  }
}

// Paused before a trial, the experimenter redoes the last trial and skips the one after it;
// both are applied by the session thread with their reasons, and a refused decision comes
// back with the store's message.
TEST(SessionControl, PauseHoldsAndDecisionsApplyBetweenTrials) {
  const Protocol protocol = read_protocol(kStudy);
  const std::string path = enrolled_study("control_pause.db", protocol);
  store::StudyStore db(path);
  PipelineTrialDriver driver(scripted_tracker());
  SessionRunner runner(db, driver, fixed_responder());
  SessionControl control;
  std::atomic<int> ended{0};
  std::atomic<bool> held{false};
  std::vector<std::string> errors;
  control.trial_ended = [&](const TrialSetup& setup, const TrialRun&) {
    if (++ended == 2) control.set_paused(true);
    if (setup.planned.position == 3) control.request_stop();
  };
  control.holding = [&] { held = true; };
  control.decided = [&](const TrialDecision&, const std::string& error) {
    errors.push_back(error);
  };
  runner.attach(&control);
  std::thread experimenter([&] {
    while (!held) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    control.decide({TrialDecision::Kind::kRedo, 1, "tracking lost"});
    control.decide({TrialDecision::Kind::kSkip, 2, "participant asked for a break"});
    control.decide({TrialDecision::Kind::kRedo, 9, "not run yet"});  // refused
    control.set_paused(false);
  });
  const SessionReport report = runner.run("P01", "scripted", false);
  experimenter.join();
  EXPECT_TRUE(report.stopped);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0], "");
  EXPECT_EQ(errors[1], "");
  EXPECT_NE(errors[2], "");
  const auto trials = db.trials("P01");
  // 0, 1 (redone), 2 skipped, 1 again, 3.
  ASSERT_EQ(trials.size(), 5u);
  EXPECT_EQ(trials[1].status, store::TrialStatus::kRedone);
  EXPECT_EQ(trials[1].reason, "tracking lost");
  EXPECT_EQ(trials[2].position, 2);
  EXPECT_EQ(trials[2].status, store::TrialStatus::kSkipped);
  EXPECT_EQ(trials[2].reason, "participant asked for a break");
  EXPECT_EQ(trials[3].position, 1);
  EXPECT_EQ(trials[3].attempt, 2);
  EXPECT_EQ(trials[4].position, 3);
  EXPECT_EQ(trials[4].status, store::TrialStatus::kCompleted);
}

// A live tracker: frames pulled without blocking, the hand held, the session paced in real
// time, the open palm calibrated step by step from what arrives.
TEST(SessionControl, LiveTrackerCalibratesFromTheHeldPalmAndRunsInRealTime) {
  // A recording whose hand is held open and still for two seconds.
  const auto recording =
      tracking::read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch-57fps.json.lz");
  // A live source that hands out the recording's frames at their own pace.
  struct Live : tracking::LiveFrameSource {
    const std::vector<tracking::TrackedFrame>* frames;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::size_t next_index = 0;
    std::chrono::steady_clock::time_point arrival(std::size_t k) const {
      return start +
             std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                 std::chrono::duration<double>((*frames)[k].timestamp - frames->front().timestamp));
    }
    std::optional<tracking::TrackedFrame> next() override {
      const auto now = std::chrono::steady_clock::now();
      std::optional<tracking::TrackedFrame> newest;
      while (next_index < frames->size() && arrival(next_index) <= now)
        newest = (*frames)[next_index++];
      return newest;
    }
    bool wait_for_frame(std::chrono::steady_clock::time_point deadline) override {
      if (next_index == frames->size()) {
        std::this_thread::sleep_until(deadline);
        return false;
      }
      const auto at = arrival(next_index);
      std::this_thread::sleep_until(std::min(at, deadline));
      return at <= deadline;
    }
  };
  const Protocol protocol = read_protocol(kStudy);
  PipelineTrialDriver driver(live_tracker("live (test)", [&] {
    auto live = std::make_unique<Live>();
    live->frames = &recording.frames;
    return live;
  }));
  SessionControl control;
  std::vector<CalibrationStatus::State> states;
  control.calibration = [&](const CalibrationStatus& s) {
    if (states.empty() || states.back() != s.state) states.push_back(s.state);
  };
  driver.attach(&control);
  std::thread watchdog([&] {  // a calibration that never finishes fails instead of hanging
    for (int k = 0; k < 1000 && !control.stop_requested(); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    control.request_stop();
  });
  retarget::Calibration c;
  try {
    c = driver.calibrate(protocol, test::participant("P01"));
  } catch (const SessionStopped&) {
    ADD_FAILURE() << "no calibration in 10 s";
  }
  control.request_stop();
  watchdog.join();
  SessionControl trial_control;
  driver.attach(&trial_control);
  ASSERT_FALSE(states.empty());
  EXPECT_EQ(states.back(), CalibrationStatus::State::kDone);
  EXPECT_GT(c.scale, 1.0);
  EXPECT_LT(c.scale, 1.6);

  TrialSetup setup;
  setup.protocol = &protocol;
  setup.condition = protocol.conditions().front();
  setup.participant = test::participant("P01");
  setup.calibration = c;
  int steps = 0;
  trial_control.stepped = [&](const TrialStep&) {
    if (++steps == 60) trial_control.request_stop();
  };
  const auto start = std::chrono::steady_clock::now();
  const TrialRun run = driver.run(setup, [](const store::FrameRecord&) {});
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(run.aborted);
  EXPECT_EQ(run.frames, 60);
  EXPECT_GE(wall, 59.0 / 120.0) << "paced at 120 Hz of wall-clock time, at most a step early";
}

// The open-palm step on frames: a refusal for two hands, for none and for a moving hand,
// each restarting the countdown; done after the hold with the palm placed above zone A.
TEST(OpenPalmCalibration, RefusesWithAReasonAndCountsDownWhileHeldStill) {
  const Protocol protocol = read_protocol(kStudy);
  const hand::Skeleton sim =
      hand::build_simulated_hand(protocol.conditions().front().simulated_hand);
  OpenPalmCalibration step(protocol.scene, sim, 0.18);
  tracking::TrackedHand hand;
  hand.side = tracking::Side::kRight;
  const auto recording =
      tracking::read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/confidence2.json.lz");
  for (const auto& f : recording.frames)
    if (const auto* h = f.hand(tracking::Side::kRight)) hand = *h;
  hand.grab_strength = 0.0;
  auto frame_at = [&](double t, Eigen::Vector3d offset, int hands = 1) {
    tracking::TrackedFrame f;
    f.timestamp = t;
    for (int k = 0; k < hands; ++k) {
      tracking::TrackedHand h = hand;
      h.palm_position += offset;
      for (auto& digit : h.joints)
        for (auto& joint : digit) joint += offset;
      if (k == 1) h.side = tracking::Side::kLeft;
      f.hands.push_back(h);
    }
    return f;
  };
  using State = CalibrationStatus::State;
  EXPECT_EQ(step.feed(frame_at(0.0, {0, 0, 0}, 0)).state, State::kNoHand);
  EXPECT_EQ(step.feed(frame_at(0.01, {0, 0, 0}, 2)).state, State::kTwoHands);
  EXPECT_EQ(step.feed(frame_at(0.02, {0, 0, 0})).state, State::kHolding);
  EXPECT_NEAR(step.feed(frame_at(1.02, {0, 0, 0})).remaining_s, 1.0, 1e-9);
  EXPECT_EQ(step.feed(frame_at(1.03, {0.01, 0, 0})).state, State::kMoving);  // 1 m/s
  tracking::TrackedFrame closed = frame_at(1.04, {0.01, 0, 0});
  closed.hands[0].grab_strength = 0.9;
  EXPECT_EQ(step.feed(closed).state, State::kClosed);
  EXPECT_EQ(step.status().message(), "The hand is closed: open it, fingers spread and flat.");
  double t = 1.05;
  for (; !step.done() && t < 5.0; t += 0.01) step.feed(frame_at(t, {0.01, 0, 0}));
  ASSERT_TRUE(step.done());
  EXPECT_NEAR(t, 1.05 + 2.0, 0.02) << "two seconds held, counted again from the refusal";
  const retarget::Calibration c = *step.status().result;
  const Eigen::Vector3d placed =
      c.tracker_to_scene * (hand.palm_position + Eigen::Vector3d(0.01, 0, 0));
  EXPECT_TRUE(placed.isApprox(protocol.scene.zone_a + Eigen::Vector3d(0, 0.12, 0), 1e-9));
  EXPECT_NE(step.status().message().find("Calibrated: scale"), std::string::npos);
}

}  // namespace
}  // namespace handlab::studies
