// The trial pipeline (scripted tracker -> retargeting -> grasp proxy -> task) and the session
// runner against a real study database.
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "core/store/frame_record.h"
#include "core/store/study_store.h"
#include "studies/export/study_export.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_control.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

using test::kStudy;

// Every condition, for a small and a large hand: the scripted pinch lifts the cube 10 cm
// (it only moves when held), carries it and puts it down inside B.
TEST(PipelineTrialDriver, ScriptedPickAndPlaceSucceedsInEveryCondition) {
  const Protocol protocol = read_protocol(kStudy);
  PipelineTrialDriver driver(scripted_tracker());
  for (double length : {0.165, 0.205}) {
    const store::Participant p = test::participant("S", length);
    const retarget::Calibration calibration = driver.calibrate(protocol, p);
    // The open-palm boxes of the two morphologies differ a little: ~6 % above the length ratio.
    EXPECT_NEAR(calibration.scale, 0.214 / length, 0.08 * 0.214 / length);
    for (const Condition& c : protocol.conditions()) {
      TrialSetup setup;
      setup.protocol = &protocol;
      setup.condition = c;
      setup.participant = p;
      setup.calibration = calibration;
      double highest = 0.0;
      store::FrameRecord last;
      long frames = 0;
      const TrialRun run = driver.run(setup, [&](const store::FrameRecord& f) {
        highest = std::max(highest, double(f.cube_position.y()));
        last = f;
        ++frames;
      });
      const std::string what = c.label + " at " + std::to_string(length);
      EXPECT_TRUE(run.success) << what;
      EXPECT_EQ(run.grasps, 1) << what;
      EXPECT_EQ(run.drops, 0) << what;
      EXPECT_EQ(run.frames, frames) << what;
      // The script raises the hand 10 cm; a grip that first touches while still closing
      // holds the cube a little lower (Naive's tips close past the first touch).
      EXPECT_GT(highest - 0.5 * c.cube_size, 0.09) << what << ": lifted";
      EXPECT_LT(std::abs(last.cube_position.x() - protocol.scene.zone_b.x()),
                0.5 * protocol.scene.zone_size)
          << what;
      EXPECT_NEAR(last.cube_position.y(), 0.5 * c.cube_size, 1e-6) << what;
      EXPECT_GT(run.completion_time_s, 3.0) << what;
      EXPECT_LT(run.completion_time_s, 8.0) << what;
      ASSERT_EQ(last.bone_positions.size(), 16u);
      EXPECT_EQ(last.angles.size(), 21u);
    }
  }
}

// The soft-hand simulator as the trial's physics: frames carry its bones and contacts, and the
// cube moves only once the flesh touches it (nothing attaches it). The built-in participant's
// open-loop pinch is planned for the proxy; on the soft hand it does not lift the cube
// (docs/study.md), so the trial's outcome is not asserted here.
TEST(PipelineTrialDriver, RunsATrialOnTheSoftHand) {
  const Protocol protocol = read_protocol(kStudy);
  PipelineTrialDriver driver(scripted_tracker(), 120.0, WorldKind::kSoftHand);
  const store::Participant p = test::participant("S", 0.18);
  TrialSetup setup;
  setup.protocol = &protocol;
  setup.condition = protocol.conditions().front();
  setup.participant = p;
  setup.calibration = driver.calibrate(protocol, p);
  long frames = 0, touching = 0, moved_untouched = 0;
  bool touched = false;
  Eigen::Vector3f start = Eigen::Vector3f::Constant(NAN);
  const TrialRun run = driver.run(setup, [&](const store::FrameRecord& f) {
    ++frames;
    ASSERT_EQ(f.bone_positions.size(), 16u);
    ASSERT_TRUE(f.bone_positions[0].allFinite());
    if (!start.allFinite()) start = f.cube_position;
    touched = touched || f.thumb_contact || f.index_contact;
    touching += f.thumb_contact || f.index_contact;
    if (!touched && (f.cube_position - start).norm() > 1e-4f) ++moved_untouched;
  });
  EXPECT_EQ(run.frames, frames);
  // One simulator step a 120 Hz frame (the first frame places the hand), each with its passes
  // and solves counted; the first factorises.
  EXPECT_GE(run.simulator.steps, frames - 1);
  EXPECT_LE(run.simulator.steps, frames);
  EXPECT_GE(run.simulator.passes, run.simulator.steps);
  EXPECT_GE(run.simulator.linear_iterations, run.simulator.factorizations);
  EXPECT_GE(run.simulator.factorizing_steps, 1);
  EXPECT_GE(run.simulator.factorizations, run.simulator.factorizing_steps);
  EXPECT_GT(run.simulator.seconds, 0.0);
  // Its time by part (StepTimer): each part timed, together no more than the steps took.
  double timed = 0.0;
  for (double part : run.simulator.timer_seconds) {
    EXPECT_GT(part, 0.0);
    timed += part;
  }
  EXPECT_LE(timed, run.simulator.seconds);
  EXPECT_GT(touching, 10) << "frames with thumb or index on the cube";
  EXPECT_EQ(moved_untouched, 0) << "the cube moved before the hand touched it";
}

// A study merged from shards may lack a place (S02 of three ran elsewhere); the next person
// enrols after the last place, with that place's schedule, not at the count of people.
TEST(Enrolment, TheNextPersonTakesThePlaceAfterTheLastEvenWithAGap) {
  const std::string path = test::fresh_path("enrolment_gap.db");
  // A Latin square: the schedule follows the place.
  std::string text = read_protocol(kStudy).text;
  text.replace(text.find("randomized-per-block"), 20, "latin-square");
  const Protocol protocol = parse_protocol(text, "latin-square.json");
  ASSERT_EQ(protocol.counterbalancing, Counterbalancing::kLatinSquare);
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  db.add_participant(test::participant("S01"), planned_rows(protocol, "S01", 0), 0);
  db.add_participant(test::participant("S03"), planned_rows(protocol, "S03", 2), 2);
  EXPECT_EQ(db.next_enrolment(), 3);
  enrol_participant(db, test::participant("P04"));
  EXPECT_EQ(db.participant("P04")->enrolment, 3);
  const auto plan = db.plan("P04");
  const auto conditions = [](const std::vector<store::PlannedTrialRow>& rows) {
    std::vector<int> ids;
    for (const auto& r : rows) ids.push_back(r.condition);
    return ids;
  };
  EXPECT_EQ(conditions(plan), conditions(planned_rows(protocol, "P04", 3)));
  EXPECT_NE(conditions(plan), conditions(planned_rows(protocol, "P04", 2)));
}

// A new study of the paper's protocol, at `name` in the tests' folder, with P01 enrolled.
std::string study_of_p01(const std::string& name) {
  const std::string path = test::fresh_path(name);
  const Protocol protocol = read_protocol(kStudy);
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  db.add_participant(test::participant("P01", 0.18), planned_rows(protocol, "P01", 0));
  return path;
}

// The session's report sums what its trials returned: a simulated participant's time by the
// cube it saw, trial by trial as each TrialRun carried it; on the grasp proxy no simulator ran.
TEST(SessionRunner, ItsReportSumsTheTrialsOwnTotals) {
  store::StudyStore db(study_of_p01("session_report_totals.db"));
  const TrackerPtr tracker = simulated_tracker(4);
  PipelineTrialDriver driver(tracker);
  SessionRunner runner(db, driver, *tracker->own_answers());
  SessionControl control;
  std::map<double, ActivityTime> seen;
  control.trial_ended = [&](const TrialSetup& setup, const TrialRun& run) {
    ASSERT_TRUE(run.experience);
    seen[setup.condition.cube_size] += run.experience->time;
  };
  runner.attach(&control);
  const SessionReport report = runner.run("P01", tracker->name(), false);
  EXPECT_TRUE(report.schedule_complete);
  EXPECT_TRUE(report.simulator.empty()) << "the grasp proxy runs no simulator";
  ASSERT_EQ(report.participant_time.size(), 2u);
  for (const auto& [cube, time] : seen) {
    const ActivityTime& summed = report.participant_time.at(cube);
    EXPECT_EQ(summed.trials, time.trials) << cube;
    EXPECT_EQ(summed.total(), time.total()) << cube;
    EXPECT_GT(summed.total(), 0.0) << cube;
  }
}

TEST(SessionRunner, RunsTheScheduleStoresEverythingAndRefusesToRestartSilently) {
  const std::string path = study_of_p01("session_runner.db");
  store::StudyStore db(path);
  PipelineTrialDriver driver(scripted_tracker());
  SessionRunner runner(db, driver, fixed_responder());
  std::vector<std::string> lines;
  const SessionReport report =
      runner.run("P01", "scripted", false, [&](const std::string& l) { lines.push_back(l); });
  EXPECT_EQ(report.trials_run, 20);
  EXPECT_TRUE(report.schedule_complete);
  EXPECT_EQ(lines.size(), 20u);

  const auto trials = db.trials("P01");
  ASSERT_EQ(trials.size(), 20u);
  for (std::size_t k = 0; k < trials.size(); ++k) {
    EXPECT_EQ(trials[k].position, int(k));
    EXPECT_EQ(trials[k].status, store::TrialStatus::kCompleted);
    store::Statement count =
        db.database().prepare("SELECT count(*), max(seq) FROM frame WHERE trial_id = ?");
    count.bind(1, trials[k].id);
    count.step();
    EXPECT_EQ(count.column_int64(0), trials[k].frames) << "no frame dropped";
    EXPECT_EQ(count.column_int64(1), trials[k].frames - 1);
  }
  {  // (statements in a scope: an unfinished one would hold its read snapshot)
    store::Statement answers = db.database().prepare("SELECT count(*) FROM answer");
    answers.step();
    EXPECT_EQ(answers.column_int64(0), 4 * 3) << "three items after each trial of the last block";
    // A frame reads back.
    store::Statement blob =
        db.database().prepare("SELECT data FROM frame WHERE trial_id = ? AND seq = 100");
    blob.bind(1, trials[5].id);
    ASSERT_TRUE(blob.step());
    const store::FrameRecord f = store::decode_frame(blob.column_blob(0));
    EXPECT_NEAR(f.time, 101.0 / 120.0, 1e-12);
    EXPECT_EQ(f.tracked.hands.size(), 1u);
  }

  // Running again without --resume is refused; with it there is nothing left.
  EXPECT_THROW(runner.run("P01", "scripted", false), std::runtime_error);
  EXPECT_TRUE(runner.run("P01", "scripted", true).schedule_complete);
  EXPECT_EQ(db.trials("P01").size(), 20u);

  // The experimenter redoes trial 3: the old result stays, marked, and the run repeats it.
  db.redo_trial("P01", 2, "participant sneezed");
  EXPECT_EQ(db.next_trial("P01")->position, 2);
  EXPECT_EQ(runner.run("P01", "scripted", true).trials_run, 1);
  const auto after = db.trials("P01");
  ASSERT_EQ(after.size(), 21u);
  EXPECT_EQ(after[2].status, store::TrialStatus::kRedone);
  EXPECT_EQ(after[2].reason, "participant sneezed");
  EXPECT_EQ(after[20].position, 2);
  EXPECT_EQ(after[20].attempt, 2);
  EXPECT_DOUBLE_EQ(after[20].completion_time_s, after[2].completion_time_s) << "deterministic";

  const auto status = study_status(db);
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].trials_planned, 20);
  EXPECT_EQ(status[0].trials_completed, 20);
  EXPECT_FALSE(status[0].next);
}

}  // namespace
}  // namespace handlab::studies

namespace handlab::studies {
namespace {

// Another design: the simulated hand's size as a factor, Latin-square orders, one block.
TEST(SessionRunner, HandSizeFactorRescalesTheCalibrationPerCondition) {
  const std::string text = R"({
    "format": "handlab-protocol", "version": 1, "name": "hand-sizes", "seed": 5,
    "factors": [{"name": "hand_length", "levels": [{"name": "small", "length": 0.17},
                                                   {"name": "large", "length": 0.23}]}],
    "blocks": 1, "counterbalancing": "latin-square",
    "scene": {"cube_size": 0.03}, "simulated_hand": {"length": 0.2, "tissue": 1.1}})";
  const Protocol protocol = parse_protocol(text, "hand-sizes.json");
  const auto conditions = protocol.conditions();
  ASSERT_EQ(conditions.size(), 2u);
  EXPECT_DOUBLE_EQ(conditions[1].simulated_hand.length, 0.23);
  EXPECT_DOUBLE_EQ(conditions[1].simulated_hand.tissue, 1.1);
  const std::string path = test::fresh_path("hand_sizes.db");
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  db.add_participant(test::participant("H1", 0.19), planned_rows(protocol, "H1", 0));
  // The real pipeline, watched: which calibration each condition's trial received.
  struct Watching : TrialDriver {
    PipelineTrialDriver real{scripted_tracker()};
    std::map<std::string, double> scale;
    retarget::Calibration calibrate(const Protocol& p, const store::Participant& who) override {
      return real.calibrate(p, who);
    }
    TrialRun run(const TrialSetup& setup, const FrameSink& sink) override {
      scale[setup.condition.label] = setup.calibration.scale;
      return real.run(setup, sink);
    }
  } driver;
  SessionRunner runner(db, driver, fixed_responder());
  EXPECT_EQ(runner.run("H1", "scripted", false).trials_run, 2);
  EXPECT_NEAR(driver.scale["large"] / driver.scale["small"], 0.23 / 0.17, 1e-12);
  EXPECT_NEAR(driver.scale["small"], 0.17 / 0.19, 0.08 * 0.17 / 0.19);
  for (const store::TrialRow& t : db.trials("H1")) {
    EXPECT_EQ(t.status, store::TrialStatus::kCompleted) << t.position;
    EXPECT_EQ(t.grasps, 1) << t.position;
  }
}

}  // namespace
}  // namespace handlab::studies
