// What a simulated participant carries from trial to trial: the law of practice, the two-rate
// adaptation of where it expects contact, its memory's record, a session that keeps it across
// a stop and a resume; and its own inverse kinematics.
#include <cmath>

#include <gtest/gtest.h>

#include "core/hand/tracked_hand.h"
#include "core/store/study_store.h"
#include "studies/participant/motor_primitives.h"
#include "studies/participant/participant_memory.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/pinch_ik.h"
#include "studies/session/session_control.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

TEST(LawOfPractice, ExponentialFromOneTowardsItsFloor) {
  EXPECT_EQ(practice_factor(1, 0.35, 0.6), 1.0);
  EXPECT_EQ(practice_factor(0, 0.35, 0.6), 1.0);  // before the first counts as the first
  EXPECT_NEAR(practice_factor(2, 0.35, 0.6), 0.6 + 0.4 * std::exp(-0.35), 1e-15);
  EXPECT_NEAR(practice_factor(11, 0.5, 0.6), 0.6 + 0.4 * std::exp(-5.0), 1e-15);
  EXPECT_NEAR(practice_factor(1000, 0.5, 0.6), 0.6, 1e-12);
  for (int n = 1; n < 30; ++n)
    EXPECT_LT(practice_factor(n + 1, 0.35, 0.6), practice_factor(n, 0.35, 0.6));
}

// The two-state model's update by hand, and its response to a constant error: the fast state
// rises first, the slow one takes over, the sum approaches B_f/(1-A_f) + B_s/(1-A_s) of it.
TEST(TwoRateAdaptation, FollowsTheStateSpaceModel) {
  const TwoRateRates r{0.59, 0.21, 0.992, 0.02};
  const TwoRateState one = adapt({}, r, 0.01);
  EXPECT_DOUBLE_EQ(one.fast, 0.0021);
  EXPECT_DOUBLE_EQ(one.slow, 0.0002);
  const TwoRateState two = adapt(one, r, -0.01);
  EXPECT_DOUBLE_EQ(two.fast, 0.59 * 0.0021 - 0.0021);
  EXPECT_NEAR(two.slow, 0.992 * 0.0002 - 0.0002, 1e-18);
  EXPECT_DOUBLE_EQ(forget(one, r).fast, 0.59 * 0.0021);
  TwoRateState s;
  for (int k = 0; k < 5000; ++k) s = adapt(s, r, 1.0);
  EXPECT_NEAR(s.fast, 0.21 / 0.41, 1e-9);
  EXPECT_NEAR(s.slow, 0.02 / 0.008, 1e-6);
}

TEST(ParticipantMemory, KeepsEachCubeApartAndRoundTripsItsRecord) {
  const TwoRateRates r{0.59, 0.21, 0.992, 0.02};
  TrialExperience fine;
  fine.cube_size = 0.01;
  // A closing in which no pad touched the cube (only forgetting), then one whose first pad
  // touched it 4 mm sooner than expected: each closing is a movement of the two-state model.
  fine.contact_errors = {std::nullopt, 0.004};
  // Where it saw its pads' midpoint against the cube as the pad touched: 3 mm along x, 1 mm
  // back along z. A closing in which no pad touched has no aim error.
  fine.aim_errors = {{0.003, -0.001}};
  // Three cubes lost from its pads before one held: two gripped 3 mm harder, one grasped
  // 2.5 mm lower.
  fine.slips = 3;
  fine.squeeze_added = 0.006;
  fine.lowered = 0.0025;
  fine.caution_added = 2.0;
  TrialExperience gross;
  gross.cube_size = 0.06;  // no closing recorded, first grasp held: nothing to adapt
  ParticipantMemory m = remember({}, fine, r, 0.9);
  m = remember(m, gross, r, 0.9);
  m = remember(m, fine, r, 0.9);
  EXPECT_EQ(m.trials, 3);
  ASSERT_EQ(m.cubes.size(), 2u);
  const CubeMemory* f = m.cube(0.0102);  // told apart to the millimetre
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->trials, 2);
  const TwoRateState one_trial = adapt(forget({}, r), r, 0.004);
  EXPECT_DOUBLE_EQ(f->contact.fast, adapt(forget(one_trial, r), r, 0.004).fast);
  EXPECT_DOUBLE_EQ(f->contact.slow, adapt(forget(one_trial, r), r, 0.004).slow);
  EXPECT_DOUBLE_EQ(f->aim_x.fast, adapt(adapt({}, r, 0.003), r, 0.003).fast);
  EXPECT_DOUBLE_EQ(f->aim_z.slow, adapt(adapt({}, r, -0.001), r, -0.001).slow);
  EXPECT_DOUBLE_EQ(f->grip_margin, 0.012);  // what each trial's slips added, kept whole
  EXPECT_DOUBLE_EQ(f->grasp_lower, 0.005);
  EXPECT_DOUBLE_EQ(f->caution.fast, adapt(adapt({}, r, 2.0), r, 2.0).fast);
  // The grip margin and the pads' lowering are kept and decay by the count of trials without a
  // slip (Witney, Goodbody & Wolpert 2000), 0.9 a trial here; a trial with a slip keeps both
  // whole, whichever of them it changed.
  ParticipantMemory held = m;
  for (int k = 0; k < 3; ++k) held = remember(held, TrialExperience{.cube_size = 0.01}, r, 0.9);
  EXPECT_NEAR(held.cube(0.01)->grip_margin, 0.012 * 0.9 * 0.9 * 0.9, 1e-15);
  EXPECT_NEAR(held.cube(0.01)->grasp_lower, 0.005 * 0.9 * 0.9 * 0.9, 1e-15);
  EXPECT_LT(held.cube(0.01)->caution.correction(), f->caution.correction());
  TrialExperience slid_over{.cube_size = 0.01, .slips = 1, .lowered = 0.0025};
  const ParticipantMemory lowered = remember(held, slid_over, r, 0.9);
  const CubeMemory* after = lowered.cube(0.01);
  EXPECT_EQ(after->grip_margin, held.cube(0.01)->grip_margin);
  EXPECT_EQ(after->grasp_lower, held.cube(0.01)->grasp_lower + 0.0025);
  const CubeMemory* g = m.cube(0.06);
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(g->trials, 1);
  EXPECT_EQ(g->contact.correction(), 0.0);
  EXPECT_EQ(g->caution.correction(), 0.0);
  EXPECT_EQ(g->aim_x.correction(), 0.0);
  EXPECT_EQ(m.cube(0.03), nullptr);
  const std::string json = memory_to_json(m);
  EXPECT_EQ(memory_to_json(memory_from_json(json)), json);
  EXPECT_DOUBLE_EQ(memory_from_json(json).cube(0.01)->contact.slow, f->contact.slow);
  EXPECT_DOUBLE_EQ(memory_from_json(json).cube(0.01)->caution.slow, f->caution.slow);
  EXPECT_DOUBLE_EQ(memory_from_json(json).cube(0.01)->aim_z.fast, f->aim_z.fast);
  EXPECT_DOUBLE_EQ(memory_from_json(json).cube(0.01)->grip_margin, f->grip_margin);
  EXPECT_DOUBLE_EQ(memory_from_json(json).cube(0.01)->grasp_lower, f->grasp_lower);
  // A record of a model before 2.3 holds no caution, before 2.6 no aim, before 2.7 the grip
  // margin as two states: they read as none, and as their sum.
  const ParticipantMemory old =
      memory_from_json(R"({"trials":1,"cubes":[{"cube_size":0.01,"trials":1,"contact_fast":0.001,)"
                       R"("contact_slow":0.0,"grip_fast":0.002,"grip_slow":0.001}]})");
  EXPECT_DOUBLE_EQ(old.cube(0.01)->grip_margin, 0.003);
  EXPECT_EQ(old.cube(0.01)->grasp_lower, 0.0);
  EXPECT_EQ(old.cube(0.01)->caution.correction(), 0.0);
  EXPECT_EQ(old.cube(0.01)->aim_x.correction(), 0.0);
  EXPECT_THROW(memory_from_json("{\"trials\": 1}"), std::runtime_error);
}

// A simulated session on the grasp proxy keeps what the person learnt with each trial's result,
// and a session stopped between trials and resumed by a new driver (a new process) goes on
// with it: every trial's outcome and memory equal the uninterrupted session's.
TEST(ParticipantMemory, ASessionStoppedAndResumedGoesOnWithWhatItLearnt) {
  // With practice trials, which teach as any other.
  const Protocol protocol = read_protocol(test::study_with_practice());
  const SimulatedPerson person = draw_person(Population{}, 3, 4);
  auto enrolled = [&](const std::string& name) {
    const std::string path = test::fresh_path(name);
    store::StudyStore::create(path, study_definition(protocol));
    store::StudyStore db(path);
    db.add_participant(person.participant, planned_rows(protocol, person.participant.id, 0));
    db.add_simulated_person(simulated_person_row(person, 3));
    return path;
  };
  auto outcome = [](store::StudyStore& db, const std::string& id) {
    std::vector<std::string> rows;
    store::Statement s = db.database().prepare(
        "SELECT p.position, t.status, t.completion_time_s, t.grasps, m.memory FROM trial t "
        "JOIN planned_trial p ON p.id = t.planned_id LEFT JOIN simulated_memory m ON "
        "m.trial_id = t.id WHERE p.participant_id = ? ORDER BY t.id");
    s.bind(1, id);
    while (s.step())
      rows.push_back(std::to_string(s.column_int64(0)) + " " + s.column_text(1) + " " +
                     std::to_string(s.column_double(2)) + " " + std::to_string(s.column_int64(3)) +
                     " " + s.column_text(4));
    return rows;
  };
  const std::string& id = person.participant.id;
  store::StudyStore whole(enrolled("memory_whole.db"));
  {
    PipelineTrialDriver driver(simulated_tracker(3));
    SessionRunner runner(whole, driver, simulated_responder(3));
    ASSERT_TRUE(runner.run(id, "simulated", false).schedule_complete);
  }
  const std::vector<std::string> expected = outcome(whole, id);
  ASSERT_EQ(expected.size(), 24u);
  const ParticipantMemory last = memory_from_json(*whole.participant_memory(id));
  EXPECT_EQ(last.trials, 24);
  ASSERT_EQ(last.cubes.size(), 2u);
  EXPECT_EQ(last.cubes[0].trials + last.cubes[1].trials, 24);
  EXPECT_EQ(whole.simulated_person(id)->model_sha256, model_sha256());
  EXPECT_EQ(whole.simulated_person(id)->model, kParticipantModelVersion);

  store::StudyStore split(enrolled("memory_split.db"));
  {
    PipelineTrialDriver driver(simulated_tracker(3));
    SessionRunner runner(split, driver, simulated_responder(3));
    SessionControl control;
    int ended = 0;
    control.trial_ended = [&](const TrialSetup&, const TrialRun&) {
      if (++ended == 7) control.request_stop();
    };
    runner.attach(&control);
    EXPECT_TRUE(runner.run(id, "simulated", false).stopped);
  }
  EXPECT_EQ(memory_from_json(*split.participant_memory(id)).trials, 7);
  {
    PipelineTrialDriver driver(simulated_tracker(3));
    SessionRunner runner(split, driver, simulated_responder(3));
    ASSERT_TRUE(runner.run(id, "simulated", true).schedule_complete);
  }
  EXPECT_EQ(outcome(split, id), expected);
}

// Its inverse kinematics puts reachable points where it wants them, inside the joints' limits,
// and holds a joint at its limit when the goal lies beyond.
TEST(PinchIk, ReachesReachableGoalsWithinTheJointLimits) {
  const hand::Skeleton s = hand::build_tracked_hand(hand::HandShape::with_length(0.19));
  const int index = s.bone_index("index_distal");
  const int thumb = s.bone_index("thumb_distal");
  const Eigen::Vector3d tip(0, s.bones[std::size_t(index)].length, 0);
  const Eigen::Vector3d thumb_tip(0, s.bones[std::size_t(thumb)].length, 0);
  // Goals a known pose reaches: the solver finds a pose that reaches them as well.
  hand::HandPose known = hand::HandPose::rest(s);
  for (std::size_t k = 0; k < s.dofs.size(); ++k)
    known.angles(Eigen::Index(k)) = s.dofs[k].lower + 0.4 * (s.dofs[k].upper - s.dofs[k].lower);
  const hand::BoneFrames f = hand::forward_kinematics(s, known);
  const std::vector<PointGoal> goals = {
      {index, tip, hand::bone_point(f, index, tip), 1.0},
      {thumb, thumb_tip, hand::bone_point(f, thumb, thumb_tip), 1.0}};
  hand::HandPose pose = hand::HandPose::rest(s);
  const PinchIkResult r = solve_pinch_ik(s, pose, goals);
  EXPECT_LT(r.residual, 1e-4);
  for (std::size_t k = 0; k < s.dofs.size(); ++k) {
    EXPECT_GE(pose.angles(Eigen::Index(k)), s.dofs[k].lower);
    EXPECT_LE(pose.angles(Eigen::Index(k)), s.dofs[k].upper);
  }
  // A fingertip goal far beyond reach with the wrist held: the residual stays, limits hold.
  hand::HandPose held = hand::HandPose::rest(s);
  PinchIkOptions options;
  options.root_weight = 1e6;
  const std::vector<PointGoal> far = {{index, tip, Eigen::Vector3d(0, -1, 0), 1.0}};
  EXPECT_GT(solve_pinch_ik(s, held, far, options).residual, 0.5);
  bool at_limit = false;
  for (std::size_t k = 0; k < s.dofs.size(); ++k) {
    const double a = held.angles(Eigen::Index(k));
    EXPECT_GE(a, s.dofs[k].lower);
    EXPECT_LE(a, s.dofs[k].upper);
    at_limit = at_limit || a == s.dofs[k].lower || a == s.dofs[k].upper;
  }
  EXPECT_TRUE(at_limit);
}

}  // namespace
}  // namespace handlab::studies
