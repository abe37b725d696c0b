// Studies side by side (`handlab-cli replications`): each study's tests are its analysis's,
// pairs of cells named and signed in the protocol's order whatever order the data had, each
// test described over the studies, and the published study's values matched by name.
// The real inputs: simulated N = 20 studies of the ISMAR 2021 protocol on the soft hand
// (tests/data/studies, made by `handlab-cli simulate --participants 20 --seed S --jobs 2`).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "core/util/json_value.h"
#include "studies/analysis/study_series.h"
#include "studies/protocol/protocol.h"
#include "studies/session/session_runner.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

const std::string kSource = HANDLAB_SOURCE_DIR;
const std::string kProtocol = kSource + "/studies/fine-manipulation-2021.json";
const std::string kPublished = kSource + "/studies/fine-manipulation-2021-published.json";

// A copy of a committed study database (opening a study may write to it), named after the test
// that asks: CTest runs the tests of this file side by side.
std::string simulated_study(int seed) {
  const ::testing::TestInfo* asking = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string copy =
      test::fresh_path(std::string(asking->test_suite_name()) + "_" + asking->name() + "_seed" +
                       std::to_string(seed) + ".db");
  std::filesystem::copy_file(
      kSource + "/tests/data/studies/simulated-n20-seed" + std::to_string(seed) + ".db", copy);
  return copy;
}

const StudyTest* find_test(const StudyTests& tests, const std::string& name) {
  for (const StudyTest& t : tests.tests)
    if (t.name == name) return &t;
  return nullptr;
}

const stats::PairwiseContrast* find_contrast(const analysis::AnalysisReport& r,
                                             const std::string& label) {
  for (const stats::PosthocResult& p : r.posthoc)
    for (const stats::PairwiseContrast& c : p.contrasts)
      if (c.effect == "strategy:manipulation" && c.contrast == label) return &c;
  return nullptr;
}

// Six participants whose Naive fine trials are slow and whose answers rate Ours above Naive
// in every condition; `protocol_text` may be another protocol's. With `timeouts`, participant
// p's Naive fine trials of the first p % 3 repetitions time out. Participant p drops the fine
// cube once in repetition r where p + r is a multiple of 3 (grasping it twice), and grasps the
// gross cube twice with no drop in the first repetition. Trials past `last_repetition` are not
// run; with `skip`, P01's first Naive gross trial is skipped.
std::string synthetic_study(const std::string& name, const Protocol& protocol,
                            bool timeouts = false, int last_repetition = 5, bool skip = false) {
  const std::string path = test::fresh_path(name);
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore store(path);
  const std::vector<Condition> conditions = protocol.conditions();
  for (int p = 0; p < 6; ++p) {
    store::Participant person;
    person.id = "P0" + std::to_string(p + 1);
    person.age = 25 + p;
    person.sex = p % 2 ? "F" : "M";
    person.handedness = "right";
    person.hand_length = 0.17 + 0.005 * p;
    person.vr_experience = "some";
    store.add_participant(person, planned_rows(protocol, person.id, p));
    const std::int64_t session = store.begin_session(person.id, "test");
    for (const store::PlannedTrialRow& t : store.plan(person.id)) {
      const Condition& c = conditions[std::size_t(t.condition)];
      if (t.repetition > last_repetition) continue;
      if (skip && p == 0 && c.label == "naive-gross" && t.repetition == 1) {
        store.skip_trial(person.id, t.position, session, "test");
        continue;
      }
      const bool naive = c.label.starts_with("naive"), fine = c.label.ends_with("fine");
      store::TrialOutcome outcome;
      outcome.success = true;
      outcome.completion_time_s = 5.0 + 0.3 * p + (fine ? 3.0 : 0.0) + (naive && fine ? 2.0 : 0.0) +
                                  0.1 * double((p * 7 + t.condition * 3 + t.repetition * 5) % 11);
      outcome.drops = fine && (p + t.repetition) % 3 == 0 ? 1 : 0;
      outcome.grasps = 1 + outcome.drops + (!fine && t.repetition == 1 ? 1 : 0);
      if (timeouts && naive && fine && t.repetition <= p % 3) {
        outcome.success = false;
        outcome.completion_time_s = protocol.timeout_s;
      }
      if (t.questionnaire)
        for (const QuestionnaireItem& item : protocol.items)
          outcome.answers.emplace_back(item.id, naive ? 1 + (p % 2) : 4 + (p % 2));
      store.finish_trial(store.begin_trial(t.id, session), outcome);
    }
    store.end_session(session, "finished");
  }
  return path;
}

TEST(StudyTests, NamePairsOfCellsInTheProtocolsOrderWithTheirSigns) {
  const Protocol protocol = read_protocol(kProtocol);
  const StudyDatabaseAnalysis a =
      analyze_study_database(synthetic_study("series_synthetic.db", protocol));
  const StudyTests tests = study_tests(a, power::SphericityCorrection::kAuto, 0.05);
  EXPECT_EQ(tests.warning, "");
  // The ANOVA's seven effects, the six pairs of cells, the two factors' levels on the first
  // repetition, the participant variables' effects (each of its follow-up ANOVAs that could
  // be made: four effects involve the variable), and per item Friedman and six pairs.
  int variables = 0;
  for (const ParticipantVariableAnalysis& v : a.participant_variables)
    variables += v.result ? 1 : 0;
  EXPECT_GE(variables, 2);
  // With no trial timed out the completion time without them is the same analysis again, and
  // the success rates' Friedman test and six pairs are there (every rate 1: no statistic).
  ASSERT_EQ(tests.tests.size(), 2u * (7u + 6u + 2u) + 4u * std::size_t(variables) + 7u + 3u * 7u);
  for (const stats::AnovaEffect& e : a.completion_time->anova.effects) {
    const StudyTest* left_out = find_test(tests, e.effect + " (timeouts left out)");
    ASSERT_TRUE(left_out) << e.effect;
    EXPECT_EQ(left_out->value, e.f) << e.effect;
    EXPECT_EQ(left_out->group, kTestsTimeoutsLeftOut);
  }
  ASSERT_TRUE(find_test(tests, "success_rate (Friedman)"));
  EXPECT_EQ(find_test(tests, "success_rate (Friedman)")->group, kTestsSuccess);
  const StudyTest* first_trial = find_test(tests, "strategy:repetition: naive 1 - ours 1");
  ASSERT_TRUE(first_trial);
  EXPECT_EQ(first_trial->statistic, "t");
  EXPECT_TRUE(find_test(tests, "manipulation:repetition: gross 1 - fine 1"));
  const StudyTest* hand = find_test(tests, "hand_length:manipulation (covariate)");
  ASSERT_TRUE(hand);
  EXPECT_EQ(hand->statistic, "F");
  ASSERT_EQ(hand->df.size(), 2u);
  EXPECT_EQ(hand->df[0], 1.0);  // one covariate: n - 2 error df
  EXPECT_FALSE(find_test(tests, "manipulation (covariate)")) << "only the variable's effects";
  const StudyTest* fine = find_test(tests, "strategy:manipulation: naive fine - ours fine");
  ASSERT_TRUE(fine);
  EXPECT_EQ(fine->statistic, "t");
  EXPECT_GT(fine->value, 5.0);  // Naive's fine trials are 2 s slower for every participant
  EXPECT_LT(fine->p, 0.05);
  const StudyTest* gross = find_test(tests, "strategy:manipulation: naive gross - naive fine");
  ASSERT_TRUE(gross);
  EXPECT_LT(gross->value, 0.0);  // gross is the faster: the first cell minus the second
  for (const std::string item : {"precision", "ease", "naturalness"}) {
    const StudyTest* w = find_test(tests, item + ": naive fine - ours fine (Wilcoxon)");
    ASSERT_TRUE(w) << item;
    // Every participant rated Ours 3 points higher: no positive difference Naive - Ours.
    EXPECT_EQ(w->value, 0.0) << item;
    EXPECT_TRUE(find_test(tests, item + " (Friedman)")) << item;
  }
  // Each test is the analysis's own, whichever way round the data ordered the cells.
  for (const stats::AnovaEffect& e : a.completion_time->anova.effects)
    EXPECT_EQ(find_test(tests, e.effect)->value, e.f) << e.effect;
  for (const std::string label : {"naive fine - ours fine", "ours fine - naive fine"})
    if (const stats::PairwiseContrast* c = find_contrast(*a.completion_time, label)) {
      EXPECT_EQ(std::abs(c->t), fine->value);
      EXPECT_EQ(c->p_tukey, fine->p);
    }
}

// Timed-out trials three ways: at the limit (the main analysis keeps every participant), left
// out (a participant without a completed trial in some cell is left out, as R's aov leaves
// them), and success as its own outcome: the rates' Friedman test against its value by hand.
TEST(StudyTests, TimedOutTrialsAtTheLimitLeftOutAndAsSuccess) {
  const Protocol protocol = read_protocol(kProtocol);
  const StudyDatabaseAnalysis a =
      analyze_study_database(synthetic_study("series_timeouts.db", protocol, true));
  ASSERT_TRUE(a.completion_time);
  EXPECT_EQ(a.completion_time->n_subjects, 6);
  EXPECT_EQ(a.quality.timeouts, 0 + 1 + 2 + 0 + 1 + 2);
  ASSERT_TRUE(a.time_without_timeouts.result) << a.time_without_timeouts.not_computed;
  EXPECT_EQ(a.time_without_timeouts.result->n_subjects, 2);  // P0 and P3 had no timeout
  const StudyTests tests = study_tests(a, power::SphericityCorrection::kAuto, 0.05);
  const StudyTest* at_limit = find_test(tests, "strategy:manipulation");
  const StudyTest* left_out = find_test(tests, "strategy:manipulation (timeouts left out)");
  ASSERT_TRUE(at_limit && left_out);
  EXPECT_NE(at_limit->value, left_out->value);
  EXPECT_EQ(left_out->df.back(), 1.0);  // two participants: (2 - 1) error df
  // Ranks per participant over the four conditions: with a timeout Naive fine 1, the others
  // tied at 3; without, all tied at 2.5. Column sums 9, 17, 17, 17 against 15; R's tie
  // correction: chi2 = 12 * 48 / (6 * 4 * 5 - (4 * 24 + 2 * 60) / 3) = 12, df 3.
  const StudyTest* friedman = find_test(tests, "success_rate (Friedman)");
  ASSERT_TRUE(friedman);
  EXPECT_NEAR(friedman->value, 12.0, 1e-12);
  EXPECT_NEAR(friedman->p, 0.00738316, 1e-7);  // pchisq(12, 3, lower.tail = FALSE)
  const StudyTest* pair = find_test(tests, "success_rate: naive fine - ours fine (Wilcoxon)");
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->value, 0.0);  // Naive fine never the more successful
}

// An effect judged with a sphericity correction carries that correction's df: each
// correction's own epsilon, taken from the correction (not guessed from the p it returned).
TEST(StudyTests, CorrectedEffectsCarryTheirCorrectionsDf) {
  const StudyDatabaseAnalysis a = analyze_study_database(simulated_study(1));
  ASSERT_TRUE(a.completion_time);
  using power::SphericityCorrection;
  int corrected = 0;
  for (const SphericityCorrection c :
       {SphericityCorrection::kNone, SphericityCorrection::kGreenhouseGeisser,
        SphericityCorrection::kHuynhFeldt}) {
    const StudyTests tests = study_tests(a, c, 0.05);
    for (const stats::AnovaEffect& e : a.completion_time->anova.effects) {
      const StudyTest* t = find_test(tests, e.effect);
      ASSERT_TRUE(t) << e.effect;
      ASSERT_EQ(t->df.size(), 2u);
      const bool one_df = e.df_num <= 1;
      const double scale = one_df || c == SphericityCorrection::kNone ? 1.0
                           : c == SphericityCorrection::kGreenhouseGeisser
                               ? e.eps_gg
                               : std::min(1.0, e.eps_hf);
      const double p = one_df || c == SphericityCorrection::kNone      ? e.p
                       : c == SphericityCorrection::kGreenhouseGeisser ? e.p_gg
                                                                       : e.p_hf;
      EXPECT_EQ(t->df[0], scale * e.df_num) << e.effect;
      EXPECT_EQ(t->df[1], scale * e.df_den) << e.effect;
      EXPECT_EQ(t->p, p) << e.effect;
      corrected += scale < 1.0 ? 1 : 0;
    }
  }
  // Repetition and its interactions (4 df) are corrected by both corrections in this study.
  EXPECT_GE(corrected, 4);
}

TEST(StudySeries, OneStudyIsItsOwnAnalysis) {
  const std::string db = simulated_study(1);
  const StudyDatabaseAnalysis a = analyze_study_database(db);
  SeriesOptions options;
  options.published = read_published_study(kPublished);
  const StudySeries s = summarize_series({db}, options);
  EXPECT_EQ(s.protocol, "fine-manipulation-2021");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].participants, 20);
  // What `simulate` reported of this study (docs/simulated-participants.md, the fifth).
  ASSERT_EQ(s.conditions,
            (std::vector<std::string>{"naive-gross", "naive-fine", "ours-gross", "ours-fine"}));
  const std::vector<int> completed = {100, 78, 100, 98};
  for (std::size_t c = 0; c < 4; ++c) {
    EXPECT_EQ(s.studies[0].conditions[c].planned, 100);
    EXPECT_EQ(s.studies[0].conditions[c].completed, completed[c]) << s.conditions[c];
    EXPECT_EQ(s.studies[0].conditions[c].completed + s.studies[0].conditions[c].timeouts, 100);
  }
  // Every test the publication reports is one this study made, under the same name.
  EXPECT_TRUE(s.published_unmatched.empty());
  int published = 0;
  for (const SeriesTest& t : s.tests) {
    EXPECT_EQ(t.studies, 1) << t.name;
    EXPECT_EQ(t.median, t.value[0]) << t.name;
    EXPECT_EQ(t.min, t.max) << t.name;
    EXPECT_EQ(t.rejected, t.p[0] < 0.05 ? 1 : 0) << t.name;
    published += t.published ? 1 : 0;
  }
  EXPECT_EQ(published, 23);
  const auto test = [&](const std::string& name) -> const SeriesTest& {
    for (const SeriesTest& t : s.tests)
      if (t.name == name) return t;
    ADD_FAILURE() << name;
    return s.tests.front();
  };
  // The interaction and the fine comparison as the fifth study's write-up gives them; the data
  // list Ours fine first, the analysis (as the series) names and signs it in the protocol's
  // order: "naive fine - ours fine", t = 3.34.
  EXPECT_NEAR(test("strategy:manipulation").value[0], 8.7376, 1e-4);
  EXPECT_NEAR(test("strategy:manipulation").p[0], 0.00811, 1e-5);
  ASSERT_TRUE(find_contrast(*a.completion_time, "naive fine - ours fine"));
  EXPECT_EQ(test("strategy:manipulation: naive fine - ours fine").value[0],
            find_contrast(*a.completion_time, "naive fine - ours fine")->t);
  EXPECT_NEAR(test("strategy:manipulation: naive fine - ours fine").value[0], 3.3357, 1e-4);
  EXPECT_NEAR(test("strategy:manipulation: naive fine - ours fine").p[0], 0.01674, 1e-5);
  EXPECT_NEAR(test("precision (Friedman)").value[0], 10.24, 0.005);
  EXPECT_EQ(test("strategy:manipulation").published->value, 8.78);
  EXPECT_TRUE(test("repetition").published->p_below);
  // Where the paper's statistic falls: this study's interaction (8.74) is below its 8.78, its
  // Manipulation effect (43.71) above 15.21; the gross comparison was published as p only.
  EXPECT_EQ(test("strategy:manipulation").below_published, 1);
  EXPECT_EQ(test("manipulation").below_published, 0);
  EXPECT_EQ(test("repetition").below_published, 1);
  EXPECT_EQ(test("strategy:manipulation: naive gross - ours gross").below_published, -1);
  EXPECT_EQ(test("strategy").below_published, -1);  // not published at all
  // Effect sizes by hand: the interaction's partial eta squared F df1 / (F df1 + df2) with
  // F(1, 19) = 8.7376, the fine contrast's d_z t / sqrt(20); the paper's F(1, 19) = 8.78 has
  // the 95 % interval .026 to .554 (R: tests/data/r/effect_size_reference.json), which holds
  // this study's; its t(19) = 3.52, 0.28 to 1.28.
  const SeriesTest& interaction = test("strategy:manipulation");
  EXPECT_EQ(interaction.effect, "pes");
  EXPECT_NEAR(interaction.effect_value[0], 8.7376 / (8.7376 + 19.0), 1e-5);
  EXPECT_EQ(interaction.effect_median, interaction.effect_value[0]);
  EXPECT_EQ(interaction.effect_low, interaction.effect_value[0]);
  EXPECT_NEAR(interaction.published_effect, 8.78 / 27.78, 1e-12);
  EXPECT_NEAR(interaction.published_low, 0.026199002669103678, 1e-7);
  EXPECT_NEAR(interaction.published_high, 0.55360523675721607, 1e-7);
  EXPECT_EQ(interaction.within_published, 1);
  const SeriesTest& fine = test("strategy:manipulation: naive fine - ours fine");
  EXPECT_EQ(fine.effect, "dz");
  EXPECT_NEAR(fine.effect_value[0], 3.3357 / std::sqrt(20.0), 1e-5);
  EXPECT_NEAR(fine.published_low, 0.27543730420068402, 1e-6);
  EXPECT_NEAR(fine.published_high, 1.2830934600911701, 1e-6);
  EXPECT_EQ(test("precision (Friedman)").effect, "");
  EXPECT_TRUE(std::isnan(test("precision (Friedman)").effect_value[0]));
}

// By hand from synthetic_study's pattern: for each repetition two of the six participants drop
// the fine cubes (p + r a multiple of 3), so 10 of each fine condition's 30 trials and 4 of
// each repetition's 24; the gross cubes' first repetition grasped again, 6 of 30 and 12 of 24.
// By hand from synthetic_study's pattern: for each repetition two of the six participants drop
// the fine cubes (p + r a multiple of 3), so 10 of each fine condition's 30 trials and 4 of
// each repetition's 24; the gross cubes' first repetition grasped again, 6 of 30 and 12 of 24.
// A second study stops after repetition 4 and skips one Naive gross trial of repetition 1 (it
// would have been grasped again): 8 of 24 fine trials dropped, 5 of 23 Naive gross grasped
// again; pooled, the two studies' counts add up, and its missing repetition is shown as such.
TEST(StudySeries, CountsTheTrialsThatLostTheCube) {
  const Protocol protocol = read_protocol(kProtocol);
  const std::string db = synthetic_study("series_losses.db", protocol, true);
  const CubeLosses losses = analyze_study_database(db).quality.losses;
  ASSERT_EQ(losses.by_condition.size(), 4u);
  for (const LossCount& c : losses.by_condition) {
    const bool fine = c.label.ends_with("fine");
    EXPECT_EQ(c.trials, 30) << c.label << ": timed-out trials count";
    EXPECT_EQ(c.dropped, fine ? 10 : 0) << c.label;
    EXPECT_EQ(c.grasped_again, fine ? 0 : 6) << c.label;
  }
  ASSERT_EQ(losses.by_repetition.size(), 5u);
  for (const LossCount& r : losses.by_repetition) {
    EXPECT_EQ(r.trials, 24) << r.label;
    EXPECT_EQ(r.dropped, 4) << r.label;
    EXPECT_EQ(r.grasped_again, r.label == "1" ? 12 : 0) << r.label;
  }
  const std::string shorter = synthetic_study("series_losses_shorter.db", protocol, false, 4, true);
  const CubeLosses cut = analyze_study_database(shorter).quality.losses;
  ASSERT_EQ(cut.by_repetition.size(), 4u);
  EXPECT_EQ(cut.by_condition[0].label, "naive-gross");
  EXPECT_EQ(cut.by_condition[0].trials, 23) << "the skipped trial left out";
  EXPECT_EQ(cut.by_condition[0].grasped_again, 5);
  EXPECT_EQ(cut.by_condition[1].dropped, 8);
  EXPECT_EQ(cut.by_repetition[0].trials, 23);
  EXPECT_EQ(cut.by_repetition[0].grasped_again, 11);
  const StudySeries s = summarize_series({db, shorter}, {});
  std::ostringstream markdown, json;
  write_series_markdown(s, markdown);
  EXPECT_NE(markdown.str().find("| naive-gross | 0 % (20 %) | 0 % (22 %) | 0 % (21 %) |"),
            std::string::npos)
      << markdown.str();
  EXPECT_NE(markdown.str().find("| naive-fine | 33 % (0 %) | 33 % (0 %) | 33 % (0 %) |"),
            std::string::npos);
  EXPECT_NE(markdown.str().find("| repetition 1 | 17 % (50 %) | 17 % (48 %) | 17 % (49 %) |"),
            std::string::npos);
  EXPECT_NE(markdown.str().find("| repetition 5 | 17 % (0 %) | – | 17 % (0 %) |"),
            std::string::npos);
  write_series_json(s, json);
  const util::JsonValue parsed = util::JsonValue::parse(json.str());
  const util::JsonValue& gross = parsed["studies"][1]["cube_losses"]["by_condition"][0];
  EXPECT_EQ(gross["label"].as_string(), "naive-gross");
  EXPECT_EQ(gross["trials"].as_number(), 23);
  EXPECT_EQ(gross["dropped"].as_number(), 0);
  EXPECT_EQ(gross["grasped_again"].as_number(), 5);
  EXPECT_EQ(parsed["studies"][0]["cube_losses"]["by_repetition"][0]["grasped_again"].as_number(),
            12);
}

TEST(StudySeries, DescribesEachTestOverTheStudies) {
  const std::vector<std::string> dbs = {simulated_study(1), simulated_study(2)};
  const StudySeries both = summarize_series(dbs, {});
  const StudySeries first = summarize_series({dbs[0]}, {});
  const StudySeries second = summarize_series({dbs[1]}, {});
  ASSERT_EQ(both.studies.size(), 2u);
  // The second study (seed 2): Naive fine completed 60 of 100, Ours fine 98.
  EXPECT_EQ(both.studies[1].conditions[1].completed, 60);
  EXPECT_EQ(both.studies[1].conditions[3].completed, 98);
  ASSERT_EQ(both.tests.size(), first.tests.size());
  ASSERT_EQ(both.tests.size(), second.tests.size());
  int differ = 0;
  for (std::size_t i = 0; i < both.tests.size(); ++i) {
    const SeriesTest& t = both.tests[i];
    ASSERT_EQ(t.name, first.tests[i].name);
    ASSERT_EQ(t.name, second.tests[i].name);
    EXPECT_EQ(t.studies, 2) << t.name;
    EXPECT_EQ(t.value[0], first.tests[i].value[0]) << t.name;
    EXPECT_EQ(t.value[1], second.tests[i].value[0]) << t.name;
    if (!std::isnan(t.p[1]) || !std::isnan(second.tests[i].p[0])) {  // NaN: no statistic
      EXPECT_EQ(t.p[1], second.tests[i].p[0]) << t.name;
    }
    // Of two values the median is their mean.
    EXPECT_DOUBLE_EQ(t.median, 0.5 * (t.value[0] + t.value[1])) << t.name;
    EXPECT_EQ(t.min, std::min(t.value[0], t.value[1])) << t.name;
    EXPECT_EQ(t.max, std::max(t.value[0], t.value[1])) << t.name;
    EXPECT_EQ(t.rejected, first.tests[i].rejected + second.tests[i].rejected) << t.name;
    differ += t.value[0] != t.value[1] ? 1 : 0;
  }
  EXPECT_GT(differ, 30);  // two studies, not one twice

  // Where the paper falls between two different studies: its interaction F (8.78) and fine t
  // (3.52) between theirs (8.74 and 48.76; 3.34 and 7.99), its Repetition F (10.01) above
  // both (1.77, 1.61), its Manipulation F (15.21) below both (43.71, 80.38).
  SeriesOptions options;
  options.published = read_published_study(kPublished);
  const StudySeries beside = summarize_series(dbs, options);
  const auto below = [&](const std::string& name) {
    for (const SeriesTest& t : beside.tests)
      if (t.name == name) return t.below_published;
    ADD_FAILURE() << name;
    return -2;
  };
  EXPECT_EQ(below("strategy:manipulation"), 1);
  EXPECT_EQ(below("strategy:manipulation: naive fine - ours fine"), 1);
  EXPECT_EQ(below("repetition"), 2);
  EXPECT_EQ(below("manipulation"), 0);
}

TEST(StudySeries, RefusesStudiesOfAnotherProtocolAndTestsNoStudyMade) {
  const std::string db = simulated_study(1);
  std::string text = test::file_bytes(kProtocol);
  text.replace(text.find("\"blocks\": 5"), 11, "\"blocks\": 2");
  const Protocol other = parse_protocol(text, "two blocks");
  const std::string two_blocks = synthetic_study("series_two_blocks.db", other);
  try {
    summarize_series({db, two_blocks}, {});
    ADD_FAILURE() << "a study of another protocol was summarised";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another protocol"), std::string::npos) << e.what();
  }
  SeriesOptions only;
  only.only = {"strategy:manipulation", "strategy:manipulation: ours fine - naive fine"};
  EXPECT_THROW(summarize_series({db}, only), std::runtime_error);  // named the other way round
  only.only.pop_back();
  EXPECT_EQ(summarize_series({db}, only).tests.size(), 1u);
  SeriesOptions foreign;
  foreign.published = read_published_study(kPublished);
  foreign.published->protocol = "another-study";
  EXPECT_THROW(summarize_series({db}, foreign), std::runtime_error);
}

TEST(PublishedStudy, RefusesAFileThatIsNotOne) {
  const PublishedStudy paper = read_published_study(kPublished);
  EXPECT_EQ(paper.participants, 20);
  EXPECT_EQ(paper.tests.size(), 23u);
  const auto refused = [](const std::string& text) {
    const std::string path = test::fresh_path("published.json");
    std::ofstream(path) << text;
    EXPECT_THROW(read_published_study(path), std::runtime_error) << text;
  };
  const std::string head =
      R"({"format": "handlab-published-results", "version": 1, "protocol": "p", "source": "s",
          "participants": 20, "tests": )";
  refused(R"({"format": "handlab-protocol", "version": 1})");
  refused(head + R"([{"test": "a", "statistic": "F", "p": 0.01, "p_below": 0.05}]})");
  refused(head + R"([{"test": "a", "statistic": "z", "p": 0.01}]})");
  refused(head + R"([{"test": "a", "statistic": "F"}, {"test": "a", "statistic": "F"}]})");
  refused(head + R"([{"test": "a", "statistic": "F", "value": "large"}]})");
  EXPECT_THROW(read_published_study(test::fresh_path("absent.json")), std::runtime_error);
}

}  // namespace
}  // namespace handlab::studies
