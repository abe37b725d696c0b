// The study database's analysis (`analyze --db`, the app's Analysis view): its per-condition
// summaries are over the participants the ANOVA analysed, so a figure's n and means agree
// with the table beside it; and a study whose participants have not reached the
// questionnaire yet is analysed, not refused.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "studies/analysis/study_database_analysis.h"
#include "studies/protocol/protocol.h"
#include "studies/session/session_runner.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

// A completion time with a participant, condition and repetition effect and some noise.
double time_of(int participant, int condition, int repetition) {
  return 5.0 + 0.7 * condition + 0.3 * participant - 0.2 * repetition +
         0.05 * double((participant * 7 + condition * 3 + repetition * 5) % 11);
}

TEST(StudyDatabaseAnalysis, SummariesLeaveOutWhomTheAnovaLeftOut) {
  const Protocol protocol =
      read_protocol(std::string(HANDLAB_SOURCE_DIR) + "/studies/fine-manipulation-2021.json");
  const std::string path = test::fresh_path("analysis_left_out.db");
  store::StudyStore::create(path, study_definition(protocol));
  {
    store::StudyStore store(path);
    for (int p = 0; p < 4; ++p) {
      store::Participant person;
      person.id = "P0" + std::to_string(p + 1);
      person.age = 30;
      person.sex = "F";
      person.handedness = "right";
      person.hand_length = 0.18;
      person.vr_experience = "some";
      store.add_participant(person, planned_rows(protocol, person.id, p));
      const std::int64_t session = store.begin_session(person.id, "test");
      int done = 0;
      for (const store::PlannedTrialRow& t : store.plan(person.id)) {
        if (p == 3 && done == 12) break;  // P04 stops half way: no full set of cells
        const std::int64_t trial = store.begin_trial(t.id, session);
        store::TrialOutcome outcome;
        outcome.success = true;
        outcome.completion_time_s = time_of(p, t.condition, t.repetition);
        store.finish_trial(trial, outcome);
        ++done;
      }
      store.end_session(session, p == 3 ? "stopped" : "finished");
    }
  }
  // No answers stored (none were given here): the times are analysed all the same.
  const StudyDatabaseAnalysis a = analyze_study_database(path);
  EXPECT_FALSE(a.questionnaire);
  EXPECT_TRUE(a.items_by_condition.empty());
  EXPECT_EQ(a.completion_time->n_subjects, 3);
  EXPECT_EQ(a.completion_time->dropped_subjects, std::vector<std::string>{"P04"});
  const std::vector<Condition> conditions = protocol.conditions();
  ASSERT_EQ(a.time_by_condition.size(), conditions.size());
  for (const CellSummary& cell : a.time_by_condition) {
    EXPECT_EQ(cell.n, 3);
    // The condition whose levels these are, and its mean over P01-P03's repetition means.
    int condition = -1;
    std::string label;
    for (const std::string& level : cell.levels) label += (label.empty() ? "" : "-") + level;
    for (std::size_t c = 0; c < conditions.size(); ++c)
      if (conditions[c].label == label) condition = int(c);
    ASSERT_GE(condition, 0);
    double sum = 0;
    for (int p = 0; p < 3; ++p) {
      double participant = 0;
      for (int r = 1; r <= protocol.blocks; ++r) participant += time_of(p, condition, r);
      sum += participant / protocol.blocks;
    }
    EXPECT_NEAR(cell.mean, sum / 3.0, 1e-9);
  }
  for (const auto& [factor, cells] : a.time_by_repetition)
    for (const CellSummary& cell : cells) EXPECT_EQ(cell.n, 3) << factor;
}

}  // namespace
}  // namespace handlab::studies
