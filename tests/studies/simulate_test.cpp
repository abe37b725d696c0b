// A whole simulated study on the grasp proxy (fast): everyone enrolled and marked simulated,
// every planned trial run, and the database's content set by the seed alone, whatever the
// number of threads that ran the sessions.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "core/util/sha256.h"
#include "studies/simulate/simulated_study.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

using test::kStudy;

// Every row of every table but the wall-clock columns (*_at), in id order.
std::string content(const std::string& path) {
  store::Database db(path, store::Database::Mode::kReadOnly);
  std::ostringstream out;
  const std::pair<const char*, int> queries[] = {
      {"SELECT name, protocol_sha256, seed, factors FROM study", 4},
      {"SELECT id, label, levels FROM condition ORDER BY id", 3},
      {"SELECT id, enrolment, age, sex, handedness, hand_length, vr_experience, notes, simulated "
       "FROM participant ORDER BY enrolment",
       9},
      {"SELECT id, participant_id, position, block, order_in_block, condition_id, repetition, "
       "practice, questionnaire FROM planned_trial ORDER BY id",
       9},
      {"SELECT id, participant_id, tracker, status FROM session ORDER BY id", 4},
      {"SELECT id, planned_id, session_id, attempt, status, completion_time_s, grasps, drops, "
       "reason, frames FROM trial ORDER BY id",
       10},
      {"SELECT id, trial_id, t, kind FROM event ORDER BY id", 4},
      {"SELECT trial_id, item, value FROM answer ORDER BY trial_id, item", 3},
      {"SELECT count(*) FROM frame", 1},
  };
  for (const auto& [query, columns] : queries) {
    store::Statement s = db.prepare(query);
    out << query << "\n";
    while (s.step()) {
      for (int c = 0; c < columns; ++c)
        out << (s.is_null(c) ? std::string("NULL") : s.column_text(c)) << "|";
      out << "\n";
    }
  }
  return out.str();
}

// What the participants did: every row of `content` but the study's and the conditions'
// (which hold the labels), and a digest of every frame.
std::string motor_data(const std::string& path) {
  std::string rows = content(path);
  rows = rows.substr(rows.find("SELECT id, enrolment"));
  store::Database db(path, store::Database::Mode::kReadOnly);
  std::string frames;
  store::Statement s = db.prepare("SELECT trial_id, seq, t, data FROM frame ORDER BY id");
  while (s.step()) {
    frames += s.column_text(0) + "|" + s.column_text(1) + "|" + s.column_text(2) + "|";
    const std::vector<std::uint8_t> data = s.column_blob(3);
    frames.append(data.begin(), data.end());
  }
  return rows + "frames " + util::sha256_hex(frames) + "\n";
}

// The study's protocol with one block (the questionnaire in the last, as in the study) and
// one practice trial per condition before it: practice trials run and count as any other.
Protocol one_block_study() {
  std::string text = read_protocol(kStudy).text;
  text = test::with(text, "\"blocks\": 5", "\"blocks\": 1");
  return parse_protocol(test::with_practice(text), "one block");
}

// Two people on the grasp proxy, side by side: quick.
SimulationOptions two_on_the_proxy() {
  SimulationOptions options;
  options.participants = 2;
  options.seed = 4;
  options.world = WorldKind::kGraspProxy;
  options.jobs = 2;
  return options;
}

// `text` with `from` (present) replaced by `to`.
using test::with;

// Labels are for people: the paper's protocol (its levels named by their methods, as before
// levels named them) and the same with every label changed and the methods written out give
// the same trials, answers and frames under the same seed.
TEST(SimulatedStudy, LabelsAreForPeopleEveryLabelRenamedTheSameMotorData) {
  std::string text = with(read_protocol(kStudy).text, "\"blocks\": 5", "\"blocks\": 1");
  const Protocol paper = parse_protocol(text, "paper");
  text = with(text, "{\"name\": \"naive\"}", "{\"name\": \"Condition A\", \"method\": \"naive\"}");
  text = with(text, "{\"name\": \"ours\"}", "{\"name\": \"Condition B\", \"method\": \"ours\"}");
  text = with(text, "{\"name\": \"gross\"", "{\"name\": \"large\"");
  text = with(text, "{\"name\": \"fine\"", "{\"name\": \"small\"");
  const Protocol renamed = parse_protocol(text, "renamed");
  ASSERT_EQ(renamed.conditions()[3].label, "Condition B-small");
  SimulationOptions options;
  options.participants = 2;
  options.seed = 9;
  options.world = WorldKind::kGraspProxy;
  options.jobs = 2;
  options.frames = true;
  const std::string a = test::fresh_path("labels_paper.db"), b = test::fresh_path("labels_new.db");
  simulate_study(paper, a, options);
  simulate_study(renamed, b, options);
  const std::string data = motor_data(a);
  ASSERT_GT(data.size(), 2000u);
  EXPECT_EQ(motor_data(b), data);
  store::Database db(b, store::Database::Mode::kReadOnly);
  EXPECT_EQ(db.query_text("SELECT label FROM condition WHERE id = 3"), "Condition B-small");
}

TEST(SimulatedStudy, EnrolsRunsEverySessionAndDependsOnTheSeedAlone) {
  const Protocol protocol = one_block_study();
  SimulationOptions options = two_on_the_proxy();
  const std::string a = test::fresh_path("simulated_a.db");
  int calls = 0, last_done = -1;
  const SimulationReport report =
      simulate_study(protocol, a, options, [&](const SimulationProgress& p) {
        ++calls;
        EXPECT_GE(p.participants_done, last_done);
        last_done = p.participants_done;
        EXPECT_EQ(p.participants, 2);
      });
  EXPECT_GT(calls, 0);
  EXPECT_EQ(last_done, 2);
  EXPECT_EQ(report.participants, 2);
  EXPECT_EQ(report.trials, 2 * 8);  // 4 scheduled and 4 practice each
  ASSERT_EQ(report.conditions.size(), 4u);
  int scheduled = 0;
  for (const ConditionOutcome& c : report.conditions) {
    EXPECT_EQ(c.planned, 2) << c.condition;
    EXPECT_EQ(c.not_run, 0) << c.condition;
    scheduled += c.planned;
    EXPECT_GE(c.completed, 1) << c.condition;  // the grasp proxy is forgiving
    EXPECT_EQ(c.completed + c.timeouts, c.planned) << c.condition;
  }
  EXPECT_EQ(scheduled, 8);
  {
    store::StudyStore study(a);
    const std::vector<store::Participant> people = study.participants();
    ASSERT_EQ(people.size(), 2u);
    // The questionnaire after each trial of the last block: 4 trials, 3 items, 2 people.
    EXPECT_EQ(study.database().query_text("SELECT count(*) FROM answer"), "24");
    for (const store::Participant& p : people) {
      EXPECT_TRUE(p.simulated);
      EXPECT_FALSE(study.next_trial(p.id)) << p.id << " has trials left";
      EXPECT_NE(p.notes.find("simulated participant"), std::string::npos);
    }
  }
  // No sessions' databases left behind.
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(a).parent_path()))
    EXPECT_EQ(entry.path().string().find("simulated_a.db.part"), std::string::npos);

  options.jobs = 1;
  const std::string b = test::fresh_path("simulated_b.db");
  simulate_study(protocol, b, options);
  EXPECT_EQ(content(a), content(b));

  // An existing file is refused, untouched.
  EXPECT_THROW(simulate_study(protocol, a, options), std::runtime_error);
  EXPECT_EQ(content(a), content(b));
}

// Where the participants' time went, by the cube they saw: every trial once, every frame it
// ran once (the database's frame counts), each activity of a trial that carries a cube.
TEST(SimulatedStudy, AccountsForEveryFrameOfItsParticipantsTimeByCube) {
  const Protocol protocol = one_block_study();
  SimulationOptions options = two_on_the_proxy();
  options.frames = true;  // a trial's frame count is then the frames it ran
  const std::string path = test::fresh_path("simulated_time.db");
  const SimulationReport report = simulate_study(protocol, path, options);
  ASSERT_EQ(report.participant_time.size(), 2u);
  EXPECT_EQ(report.participant_time[0].first, 0.01);
  EXPECT_EQ(report.participant_time[1].first, 0.06);
  double seconds = 0.0;
  for (const auto& [cube, t] : report.participant_time) {
    EXPECT_EQ(t.trials, 8) << cube;  // each person: 2 practice and 2 scheduled with each cube
    seconds += t.total();
    for (Activity a : {Activity::kReact, Activity::kReach, Activity::kDescend, Activity::kClose,
                       Activity::kLift, Activity::kTransport, Activity::kSetDown})
      EXPECT_GT(t[a], 0.0) << cube << " " << activity_name(a);
  }
  store::StudyStore study(path);
  const double frames =
      std::stod(study.database().query_text("SELECT sum(frames) FROM trial").value());
  EXPECT_NEAR(seconds, frames / 120.0, 1e-6);
}

}  // namespace
}  // namespace handlab::studies
