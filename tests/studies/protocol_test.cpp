// The study protocol file, its schedules and its validation.
#include <algorithm>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/util/sha256.h"
#include "studies/protocol/protocol.h"
#include "studies/session/session_runner.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::studies {
namespace {

using test::kStudy;

TEST(Protocol, TheStudyFileDescribesThePaper) {
  const Protocol p = read_protocol(kStudy);
  EXPECT_EQ(p.name, "fine-manipulation-2021");
  ASSERT_EQ(p.factors.size(), 2u);
  EXPECT_EQ(p.factors[0].name, "strategy");
  EXPECT_EQ(p.factors[1].name, "manipulation");
  const auto conditions = p.conditions();
  ASSERT_EQ(conditions.size(), 4u);
  EXPECT_EQ(conditions[0].label, "naive-gross");
  EXPECT_EQ(conditions[0].strategy.method, handlab::retarget::Strategy::kNaive);
  EXPECT_DOUBLE_EQ(conditions[0].cube_size, 0.06);
  EXPECT_EQ(conditions[3].label, "ours-fine");
  EXPECT_EQ(conditions[3].strategy.method, handlab::retarget::Strategy::kOurs);
  EXPECT_DOUBLE_EQ(conditions[3].cube_size, 0.01);
  EXPECT_DOUBLE_EQ(conditions[3].simulated_hand_length, 0.214);
  EXPECT_EQ(p.blocks, 5);
  // Five blocks of four trials and nothing before them: a participant's first trial of each
  // condition is its repetition 1, as in the paper's comparison of "the very first trial".
  EXPECT_EQ(p.practice_per_condition, 0);
  const auto schedule = plan_schedule(p, "P01", 0);
  ASSERT_EQ(schedule.size(), 20u);
  EXPECT_EQ(schedule.front().block, 1);
  EXPECT_EQ(schedule.front().repetition, 1);
  EXPECT_EQ(p.questionnaire_timing, QuestionnaireTiming::kLastBlock);
  ASSERT_EQ(p.items.size(), 3u);
  EXPECT_EQ(p.items[0].id, "precision");
  EXPECT_EQ(p.items[1].id, "ease");
  EXPECT_EQ(p.items[2].id, "naturalness");
  for (const auto& item : p.items) EXPECT_EQ(item.anchors.size(), 5u);
  EXPECT_DOUBLE_EQ(p.timeout_s, 60.0);
  EXPECT_DOUBLE_EQ(p.rest_time_s, 0.5);
  EXPECT_GT(p.text.size(), 500u);
}

TEST(Protocol, ScheduleIsReproducibleAndEveryBlockHoldsEachConditionOnce) {
  const Protocol p = read_protocol(test::study_with_practice());
  const auto a = plan_schedule(p, "P01", 0);
  ASSERT_EQ(a.size(), 4u + 20u);  // practice, then 5 blocks of 4
  const auto same = plan_schedule(p, "P01", 0);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].condition, same[k].condition);
    EXPECT_EQ(a[k].position, int(k));
  }
  std::map<int, std::set<int>> by_block;
  for (const auto& t : a) {
    EXPECT_TRUE(by_block[t.block].insert(t.condition).second) << "block " << t.block;
    EXPECT_EQ(t.practice, t.block == 0);
    EXPECT_EQ(t.questionnaire, t.block == 5);
    if (!t.practice) {
      EXPECT_EQ(t.repetition, t.block);
    }
  }
  for (int b = 0; b <= 5; ++b) EXPECT_EQ(by_block[b].size(), 4u) << "block " << b;
  // Other participants get other orders.
  int differing = 0;
  for (const char* id : {"P02", "P03", "P04", "P05"}) {
    const auto other = plan_schedule(p, id, 1);
    for (std::size_t k = 4; k < a.size(); ++k) differing += other[k].condition != a[k].condition;
  }
  EXPECT_GT(differing, 20);
}

TEST(Protocol, BalancedLatinSquares) {
  for (int n : {2, 3, 4, 5, 6}) {
    const int rows = n % 2 == 0 ? n : 2 * n;
    std::map<std::pair<int, int>, int> follows;
    std::vector<std::map<int, int>> at_place(static_cast<std::size_t>(n));
    for (int r = 0; r < rows; ++r) {
      const auto row = balanced_latin_square_row(n, r);
      std::vector<int> sorted = row;
      std::sort(sorted.begin(), sorted.end());
      for (int k = 0; k < n; ++k) ASSERT_EQ(sorted[std::size_t(k)], k);
      for (int k = 0; k + 1 < n; ++k) ++follows[{row[std::size_t(k)], row[std::size_t(k + 1)]}];
      for (int k = 0; k < n; ++k) ++at_place[std::size_t(k)][row[std::size_t(k)]];
    }
    // Every ordered pair adjacent equally often; every condition equally often at each place.
    EXPECT_EQ(int(follows.size()), n * (n - 1)) << n;
    for (const auto& [pair, count] : follows) EXPECT_EQ(count, rows / n) << n;
    for (const auto& place : at_place)
      for (const auto& [c, count] : place) EXPECT_EQ(count, rows / n) << n;
  }
}

using test::with;

// The study's protocol with its strategy levels' methods written out (the file names its
// levels naive and ours, which were their methods before levels named them).
std::string with_methods(const std::string& text) {
  return with(with(text, "{\"name\": \"naive\"}", "{\"name\": \"naive\", \"method\": \"naive\"}"),
              "{\"name\": \"ours\"}", "{\"name\": \"ours\", \"method\": \"ours\"}");
}

TEST(Protocol, RejectsWhatItDoesNotKnowWithTheKey) {
  const std::string text = with_methods(read_protocol(kStudy).text);
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {with(text, "\"name\": \"manipulation\"", "\"name\": \"glove\""), "unknown factor \"glove\""},
      {with(text, "\"blocks\": 5", "\"blokcs\": 5"), "unknown key \"blokcs\""},
      {with(text, "{\"name\": \"ours\", \"method\": \"ours\"}",
            "{\"name\": \"naive\", \"method\": \"ours\"}"),
       "factors[0].levels[1].name: the label \"naive\" is another level's of \"strategy\""},
      {with(text, "\"method\": \"ours\"", "\"method\": \"mirror\""),
       "factors[0].levels[1].method: unknown method \"mirror\" (known: naive, ours)"},
      {with(text, "{\"name\": \"naive\", \"method\": \"naive\"}",
            "{\"name\": \"naive\", \"method\": \"naive\", \"parameters\": {}}"),
       "factors[0].levels[0].parameters: method \"naive\" takes no parameters"},
      {with(text, "\"method\": \"ours\"", "\"method\": \"ours\", \"parameters\": {\"damping\": 1}"),
       "factors[0].levels[1].parameters: method \"ours\" takes no parameter \"damping\""},
      {with(text, "\"method\": \"ours\"",
            "\"method\": \"ours\", \"parameters\": {\"tip_weights\": [1, 1]}"),
       "factors[0].levels[1].parameters.tip_weights: must list five weights"},
      {with(text, "{\"name\": \"ours\", \"method\": \"ours\"}", "{\"name\": \"B\"}"),
       "factors[0].levels[1]: \"method\" is required"},
      {with(text, "\"method\": \"ours\"",
            "\"method\": \"ours\", \"parameters\": {\"spatial_weight\": 0}"),
       "factors[0].levels[1].parameters.spatial_weight: must be from 1e-12 to 0.001, is 0"},
      {with(with(with(with(text, "{\"name\": \"naive\",", "{\"name\": \"a-b\","),
                      "{\"name\": \"ours\",", "{\"name\": \"a\","),
                 "\"name\": \"gross\"", "\"name\": \"c\""),
            "\"name\": \"fine\"", "\"name\": \"b-c\""),
       "factors: two conditions would both be labelled \"a-b-c\""},
      {with(text, ",\n      {\"name\": \"fine\", \"cube_size\": 0.01}", ""),
       "factors[1].levels: a factor needs at least two levels, \"manipulation\" has 1"},
      {with(text, "\"cube_size\": 0.01", "\"cube_size\": 0.003"),
       "factors[1].levels[1].cube_size: a length in metres from 0.005 to 0.15 (5 mm to 150 mm), "
       "is 0.003 m (3 mm)"},
      {with(text, "\"cube_size\": 0.01", "\"cube_size\": 0.0005"),
       "cube_size: a length in metres from 0.005 to 0.15 (5 mm to 150 mm), is 0.0005 m (0.5 mm)"},
      {with(text, "\"cube_size\": 0.06", "\"cube_size\": 60"),
       "is 60 m (60000 mm): in metres, 60 mm is 0.06"},
      {with(text, "\"cube_size\": 0.06", "\"cube_size\": 0.2"),
       "factors[1].levels[0].cube_size: a length in metres from 0.005 to 0.15 (5 mm to 150 mm), "
       "is 0.2 m (200 mm)"},
      {with(text, "\"counterbalancing\": \"randomized-per-block\"",
            "\"counterbalancing\": \"abba\""),
       "abba"},
      {with(text, "\"cube_size\": 0.01", "\"cube_size\": -1"), "cube_size"},
      {with(text, "\"blocks\": 5", "\"blocks\": 5, \"session\": {\"display\": \"hmd\"}"),
       "session.display: is \"window\" or \"headset\""},
      {with(text, "\"blocks\": 5", "\"blocks\": 5, \"session\": {\"tracker\": \"glove\"}"),
       "session.tracker: is \"leap\", \"openxr\", \"scripted\" or \"simulated\""},
      {with(text, "\"blocks\": 5", "\"blocks\": 5, \"session\": {\"displays\": \"headset\"}"),
       "unknown key \"displays\""},
      {with(text, "\"version\": 1", "\"version\": 2"), "version 2"},
      {text.substr(0, text.size() / 2), "protocol.json"},
  };
  for (const Case& c : cases) {
    try {
      parse_protocol(c.text, "protocol.json");
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

// A protocol may name the display and tracker its sessions run with unless chosen otherwise;
// without it, a window and the front end's own tracker.
TEST(Protocol, TheSessionsDefaultDisplayAndTracker) {
  const std::string text = read_protocol(kStudy).text;
  const Protocol plain = parse_protocol(text, "protocol.json");
  EXPECT_EQ(plain.default_display, SessionDisplay::kWindow);
  EXPECT_EQ(plain.default_tracker, "");
  const Protocol headset = parse_protocol(
      with(text, "\"blocks\": 5",
           "\"blocks\": 5, \"session\": {\"display\": \"headset\", \"tracker\": \"openxr\"}"),
      "protocol.json");
  EXPECT_EQ(headset.default_display, SessionDisplay::kHeadset);
  EXPECT_EQ(headset.default_tracker, "openxr");
}

// A study made before the 5-150 mm rule (2-200 mm were allowed) still opens: its database's
// protocol is read by the rules it was made under; a new study is refused.
TEST(Protocol, AStudyMadeBeforeTheCubeRuleStillOpens) {
  const std::string text =
      with(read_protocol(kStudy).text, "\"cube_size\": 0.01", "\"cube_size\": 0.003");
  EXPECT_THROW(parse_protocol(text, "new.json"), ProtocolError);
  const Protocol old = parse_protocol(text, "old.db", ProtocolSource::kStoredStudy);
  EXPECT_EQ(old.factors[1].levels[1].cube_size, 0.003);
  EXPECT_THROW(parse_protocol(with(text, "0.003", "0.25"), "old.db", ProtocolSource::kStoredStudy),
               ProtocolError);
  const std::string path = test::fresh_path("cube_3mm.db");
  store::StudyStore::create(path, study_definition(old));
  store::StudyStore study(path, store::StudyStore::Access::kReadOnly);
  EXPECT_EQ(stored_protocol(study).factors[1].levels[1].cube_size, 0.003);
}

TEST(Protocol, AStrategyLevelNamesItsMethodAndParametersApartFromItsLabel) {
  std::string text = with_methods(read_protocol(kStudy).text);
  text = with(text, "{\"name\": \"naive\", \"method\": \"naive\"}",
              "{\"name\": \"Condition A\", \"method\": \"naive\"}");
  text = with(text, "{\"name\": \"ours\", \"method\": \"ours\"}",
              "{\"name\": \"B\", \"method\": \"ours\"}, {\"name\": \"C\", \"method\": "
              "\"ours\", \"parameters\": {\"tip_weights\": [2, 2, 1, 1, 0.5], "
              "\"spatial_weight\": 2e-8, \"max_iterations\": 8}}");
  const Protocol p = parse_protocol(text, "p.json");
  const auto conditions = p.conditions();
  ASSERT_EQ(conditions.size(), 6u);
  EXPECT_EQ(conditions[0].label, "Condition A-gross");
  EXPECT_EQ(conditions[0].strategy.method, retarget::Strategy::kNaive);
  EXPECT_EQ(conditions[2].label, "B-gross");
  EXPECT_EQ(conditions[2].strategy.method, retarget::Strategy::kOurs);
  const retarget::OursOptions defaults;
  EXPECT_EQ(conditions[2].strategy.ours.tip_weights, defaults.tip_weights);
  EXPECT_EQ(conditions[2].strategy.ours.solver.max_iterations, defaults.solver.max_iterations);
  const StrategyMethod& c = conditions[5].strategy;
  EXPECT_EQ(conditions[5].label, "C-fine");
  EXPECT_EQ(c.method, retarget::Strategy::kOurs);
  EXPECT_EQ(c.ours.tip_weights, (std::array<double, 5>{2, 2, 1, 1, 0.5}));
  EXPECT_DOUBLE_EQ(c.ours.solver.spatial_weight, 2e-8);
  EXPECT_EQ(c.ours.solver.max_iterations, 8);
  EXPECT_DOUBLE_EQ(c.ours.solver.temporal_weight, defaults.solver.temporal_weight);
  // The study's file, from before methods (a level's name was its method), reads as it did.
  const auto old = read_protocol(kStudy).conditions();
  EXPECT_EQ(old[1].strategy.method, retarget::Strategy::kNaive);
  EXPECT_EQ(old[2].strategy.method, retarget::Strategy::kOurs);
}

TEST(Protocol, TheQuestionnaireAfterTheBlocksTheProtocolLists) {
  const std::string study = read_protocol(kStudy).text;
  const Protocol p = parse_protocol(
      with(study, "\"when\": \"last-block\"", "\"when\": \"blocks\", \"blocks\": [3, 1]"),
      "p.json");
  EXPECT_EQ(p.questionnaire_blocks, (std::vector<int>{1, 3}));
  EXPECT_EQ(p.questionnaire_schedule(), "after each trial of blocks 1 and 3");
  int asked = 0;
  for (const auto& t : plan_schedule(p, "P01", 0)) {
    EXPECT_EQ(t.questionnaire, t.block == 1 || t.block == 3) << t.position;
    asked += t.questionnaire;
  }
  EXPECT_EQ(asked, 8);
  EXPECT_EQ(read_protocol(kStudy).questionnaire_schedule(), "after each trial of the last block");
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"\"when\": \"blocks\", \"blocks\": [6]",
            "questionnaire.blocks: a block is a number from 1 to 5"},
           {"\"when\": \"blocks\", \"blocks\": [2, 2]",
            "questionnaire.blocks: block 2 appears twice"},
           {"\"when\": \"blocks\"", "questionnaire.blocks: must list the blocks (1 to 5)"},
           {"\"when\": \"last-block\", \"blocks\": [2]",
            "questionnaire.blocks: needs \"when\": \"blocks\""}}) {
    try {
      parse_protocol(with(study, "\"when\": \"last-block\"", text), "q.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

TEST(Protocol, LatinSquareAndEveryTrialQuestionnaire) {
  std::string text = read_protocol(kStudy).text;
  text = with(text, "\"randomized-per-block\"", "\"latin-square\"");
  text = with(text, "\"last-block\"", "\"every-trial\"");
  const Protocol p = parse_protocol(text, "p.json");
  for (int enrolment = 0; enrolment < 4; ++enrolment) {
    const auto plan = plan_schedule(p, "X", enrolment);
    const auto row = balanced_latin_square_row(4, enrolment);
    for (const auto& t : plan) {
      if (t.practice) continue;
      EXPECT_EQ(t.condition, row[std::size_t(t.order - 1)]);
      EXPECT_TRUE(t.questionnaire);
    }
  }
}

TEST(Sha256, KnownDigests) {
  EXPECT_EQ(util::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(util::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(util::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(util::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

}  // namespace
}  // namespace handlab::studies
