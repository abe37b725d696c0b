// Between-participants factors: read from the protocol with refusals that name the field,
// assigned at enrolment (balanced in order of enrolment, or from a participant field), stored
// with the participant, exported beside the fields and shown in the protocol's summary.
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "core/store/study_merge.h"
#include "core/store/study_store.h"
#include "studies/export/study_export.h"
#include "studies/protocol/export_columns.h"
#include "studies/session/enrolment.h"
#include "studies/session/group_assignment.h"
#include "studies/session/session_runner.h"
#include "studies/simulate/simulated_study.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

const std::string kMixed =
    std::string(HANDLAB_SOURCE_DIR) + "/studies/examples/mixed-vr-experience.json";

using test::with;

// The mixed example's between array replaced by `between`.
std::string with_between(const std::string& between) {
  const std::string text = read_protocol(kMixed).text;
  const std::size_t start = text.find("\"between\"");
  const std::size_t end = text.find("\"blocks\"");
  return text.substr(0, start) + "\"between\": " + between + ",\n  " + text.substr(end);
}

TEST(BetweenFactor, TheMixedExampleReadsItsGroupsFromTheVrExperience) {
  const Protocol p = read_protocol(kMixed);
  ASSERT_EQ(p.between.size(), 1u);
  const BetweenFactor& vr = p.between[0];
  EXPECT_EQ(vr.name, "experience");
  EXPECT_EQ(vr.assignment, GroupAssignment::kParticipantField);
  EXPECT_EQ(vr.field, "vr_experience");
  ASSERT_EQ(vr.levels.size(), 2u);
  EXPECT_EQ(level_holding(vr, " Yes ")->name, "experienced");  // as a form's answer is typed
  EXPECT_EQ(level_holding(vr, "none")->name, "novice");
  EXPECT_EQ(level_holding(vr, "daily"), nullptr);
  EXPECT_EQ(p.conditions().size(), 4u);  // the groups are not conditions
}

TEST(BetweenFactor, RefusalsNameTheField) {
  const std::string two =
      R"([{"name": "g", "assignment": "enrolment", "levels": [{"name": "a"}, {"name": "b"}]}])";
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {with_between(R"([{"name": "g", "levels": [{"name": "a"}, {"name": "b"}]}])"),
       "between[0]: \"assignment\" is required"},
      {with_between(with(two, "\"enrolment\"", "\"shoe_size\"")),
       "between[0].assignment: \"shoe_size\" is not \"enrolment\" nor a participant field"},
      {with_between(with(two, ", {\"name\": \"b\"}", "")),
       "between[0].levels: a factor needs at least two levels, \"g\" has 1"},
      {with_between(with(two, "{\"name\": \"b\"}", "{\"name\": \"a\"}")),
       "between[0].levels[1].name: the label \"a\" is another level's of \"g\""},
      {with_between(with(two, "\"name\": \"g\"", "\"name\": \"strategy\"")),
       "between[0].name: \"strategy\" is taken"},
      {with_between(with(two, "\"name\": \"g\"", "\"name\": \"vr_experience\"")),
       "between[0].name: \"vr_experience\" is taken"},
      {with_between(with(two, "\"name\": \"g\"", "\"name\": \"precision\"")),
       "between[0].name: \"precision\" is taken"},
      {with_between(with(two, "\"name\": \"g\"", "\"name\": \"VR group\"")),
       "between[0].name: use letters, digits and '_'"},
      {with_between(with(two, "{\"name\": \"a\"}", "{\"name\": \"a\", \"values\": [\"none\"]}")),
       "between[0].levels[0]: unknown key \"values\""},
      {with_between(
           R"([{"name": "g", "assignment": "vr_experience", "levels": [{"name": "a", "values": ["none"]}, {"name": "b"}]}])"),
       "between[0].levels[1]: \"values\" must list the vr_experience answers"},
      {with_between(
           R"([{"name": "g", "assignment": "vr_experience", "levels": [{"name": "a", "values": ["none"]}, {"name": "b", "values": ["yes", "None"]}]}])"),
       "between[0].levels[1].values: \"None\" is a value of level \"a\" too"},
      {with_between(
           R"([{"name": "g", "assignment": "hand_length", "levels": [{"name": "small", "below": 0.18}, {"name": "large", "from": 0.17}]}])"),
       "between[0].levels[1]: its range overlaps level \"small\"'s"},
      {with_between(
           R"([{"name": "g", "assignment": "age", "levels": [{"name": "young", "below": 30}, {"name": "old", "values": ["old"]}]}])"),
       "between[0].levels[1]: unknown key \"values\""},
      {with_between(
           R"([{"name": "g", "assignment": "age", "levels": [{"name": "young", "below": 30}, {"name": "old"}]}])"),
       "between[0].levels[1]: give \"from\", \"below\" or both"},
      {with_between(two.substr(0, two.size() - 1) + ", 3]"), "between[1]: must be an object"},
      {with_between(
           R"([{"name": "g", "assignment": "sex", "levels": [{"name": "a", "values": ["F"]}, {"name": "b", "values": ["female"]}]}])"),
       "between[0].levels[1].values: \"female\" is not a sex the form takes (F, M, X)"},
      {with_between(
           R"([{"name": "g", "assignment": "hand_length", "levels": [{"name": "a", "below": 0.2}, {"name": "b", "from": 0.31}]}])"),
       "between[0].levels[1]: no participant's hand_length is in its range"},
      {with(read_protocol(kMixed).text, "{\"id\": \"ease\"", "{\"id\": \"block\""),
       "questionnaire.items[1].id: \"block\" is taken"},
  };
  for (const Case& c : cases) {
    try {
      parse_protocol(c.text, "mixed.json");
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("mixed.json: " + c.message), std::string::npos)
          << e.what();
    }
  }
}

// Every run of k enrolments holds each of the k combinations of the enrolment-assigned
// factors once; the order within a run differs between runs (drawn from the seed).
TEST(GroupAssignment, InOrderOfEnrolmentEveryRunHoldsEveryCombinationOnce) {
  const Protocol p = parse_protocol(
      with_between(
          R"([{"name": "glove", "assignment": "enrolment", "levels": [{"name": "on"}, {"name": "off"}]},
                       {"name": "vr", "assignment": "vr_experience", "levels": [{"name": "novice", "values": ["none"]}, {"name": "experienced", "values": ["some", "yes"]}]},
                       {"name": "seat", "assignment": "enrolment", "levels": [{"name": "low"}, {"name": "mid"}, {"name": "high"}]}])"),
      "crossed.json");
  std::set<std::vector<std::string>> orders;
  for (int run = 0; run < 4; ++run) {
    std::set<std::pair<std::string, std::string>> seen;
    std::vector<std::string> order;
    for (int k = 0; k < 6; ++k) {
      const store::Participant person = test::participant("P" + std::to_string(run * 6 + k));
      const auto groups = assign_groups(p, person, run * 6 + k);
      ASSERT_EQ(groups.size(), 3u);
      EXPECT_EQ(groups[0].first, "glove");
      EXPECT_EQ(groups[1], (std::pair<std::string, std::string>{"vr", "experienced"}));
      EXPECT_EQ(groups[2].first, "seat");
      EXPECT_TRUE(seen.insert({groups[0].second, groups[2].second}).second)
          << "run " << run << " repeats " << groups[0].second << " " << groups[2].second;
      order.push_back(groups[0].second + groups[2].second);
    }
    orders.insert(order);
  }
  EXPECT_GT(orders.size(), 1u) << "every run in the same order: the next group is foreseeable";
}

TEST(GroupAssignment, FromAFieldByValueOrRangeAndRefusedWhenInNoLevel) {
  const Protocol p = parse_protocol(
      with_between(
          R"([{"name": "hand", "assignment": "hand_length", "levels": [{"name": "small", "below": 0.18}, {"name": "large", "from": 0.18}]},
                       {"name": "age_group", "assignment": "age", "levels": [{"name": "young", "from": 18, "below": 40}, {"name": "older", "from": 40}]}])"),
      "ranges.json");
  store::Participant person = test::participant("P1", 0.179);
  person.age = 40;
  auto groups = assign_groups(p, person, 0);
  EXPECT_EQ(groups[0].second, "small");
  EXPECT_EQ(groups[1].second, "older");
  person.hand_length = 0.18;
  EXPECT_EQ(assign_groups(p, person, 0)[0].second, "large");
  person.hand_length = 0.1795;  // as the form takes it, in cm
  const Protocol small_only = parse_protocol(
      with_between(
          R"([{"name": "hand", "assignment": "hand_length", "levels": [{"name": "a", "from": 0.15, "below": 0.17}, {"name": "b", "from": 0.18}]}])"),
      "gap.json");
  try {
    assign_groups(small_only, person, 0);
    ADD_FAILURE() << "placed in a gap";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("The hand length 17.95 cm is in no level"),
              std::string::npos)
        << e.what();
  }
  person.hand_length = 0.18;
  person.age = 17;
  EXPECT_THROW(assign_groups(p, person, 0), std::invalid_argument);
  const auto problems = participant_problems(person, {}, &p);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "age");
  EXPECT_NE(
      problems[0].message.find("The age 17 years is in no level of the between factor age_group"),
      std::string::npos)
      << problems[0].message;
}

// Enrolled, stored, changed with the field, exported beside the fields, summarised.
TEST(GroupAssignment, StoredWithTheParticipantExportedAndSummarised) {
  const Protocol protocol = read_protocol(kMixed);
  const std::string path = test::fresh_path("groups.db");
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  store::Participant a = test::participant("A");
  a.vr_experience = "none";
  enrol_participant(db, a);
  store::Participant b = test::participant("B");
  b.vr_experience = "daily";
  try {
    enrol_participant(db, b);
    ADD_FAILURE() << "enrolled in no group";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "The vr_experience \"daily\" is in no level of the between factor experience (none, "
              "some, yes, expert).");
  }
  EXPECT_FALSE(db.participant("B"));
  b.vr_experience = "Expert";
  enrol_participant(db, b);
  EXPECT_EQ(db.participant("A")->between_levels,
            (std::vector<std::pair<std::string, std::string>>{{"experience", "novice"}}));
  EXPECT_EQ(db.participant("B")->between_levels,
            (std::vector<std::pair<std::string, std::string>>{{"experience", "experienced"}}));
  a.vr_experience = "some";  // a typing error mended: the group follows
  update_participant(db, a);
  EXPECT_EQ(db.participant("A")->between_levels[0].second, "experienced");

  std::ostringstream trials;
  write_trials_csv(db, trials);
  EXPECT_EQ(trials.str().substr(0, trials.str().find('\n')),
            "participant,age,sex,handedness,hand_length,vr_experience,experience,block,order,"
            "strategy,"
            "manipulation,repetition,completion_time_s,outcome,grasps,drops,attempt");

  std::map<std::string, std::string> summary;
  for (const auto& [label, value] : protocol_summary(protocol)) summary[label] = value;
  EXPECT_EQ(summary["Between factor experience"],
            "novice (none), experienced (some, yes, expert); by vr_experience");
  EXPECT_EQ(summary["Factor strategy"], "naive, ours");  // labels that say their method
}

// The mixed example with a second factor assigned in order of enrolment; with `one_block`, one
// block and no practice trials.
Protocol with_glove(bool one_block = false) {
  std::string text = read_protocol(kMixed).text;
  if (one_block) {
    text = test::with(text, "\"blocks\": 5", "\"blocks\": 1");
    text = test::with(text, "{\"trials_per_condition\": 1}", "{\"trials_per_condition\": 0}");
  }
  const std::size_t at = text.find("\"between\": [") + std::string("\"between\": [").size();
  return parse_protocol(
      text.substr(0, at) +
          R"({"name": "glove", "assignment": "enrolment", "levels": [{"name": "on"}, {"name": "off"}]}, )" +
          text.substr(at),
      "glove.json");
}

// A mended field moves the participant to the group it decides, but only before their
// schedule has started; a group assigned in order of enrolment never moves.
TEST(GroupAssignment, AnEditKeepsTheEnrolmentGroupAndMovesNoOneWhoseTrialsRan) {
  const Protocol protocol = with_glove();
  const std::string path = test::fresh_path("groups_edit.db");
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  store::Participant a = test::participant("A");
  a.vr_experience = "none";
  enrol_participant(db, a);
  const auto enrolled = db.participant("A")->between_levels;
  ASSERT_EQ(enrolled.size(), 2u);
  EXPECT_EQ(enrolled[0].first, "glove");
  // The stored level stays even where the enrolment order would now say otherwise.
  db.database().exec(std::string("UPDATE participant SET between_levels = '{\"glove\":\"") +
                     (enrolled[0].second == "on" ? "off" : "on") +
                     "\",\"experience\":\"novice\"}' WHERE id = 'A'");
  const auto moved = db.participant("A")->between_levels;
  a.notes = "glasses";
  a.vr_experience = "yes";
  update_participant(db, a);
  EXPECT_EQ(db.participant("A")->between_levels, (std::vector<std::pair<std::string, std::string>>{
                                                     moved[0], {"experience", "experienced"}}));
  db.begin_session("A", "x");  // the schedule has started
  a.vr_experience = "none";
  try {
    update_participant(db, a);
    ADD_FAILURE() << "moved after trials";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("would move A from experience experienced to novice"),
              std::string::npos)
        << e.what();
  }
  a.vr_experience = " YES ";  // the same group: accepted
  update_participant(db, a);
  EXPECT_EQ(db.participant("A")->vr_experience, " YES ");
}

// Shards place each person as the whole study does (the group follows the place, not the
// shard); merged, the groups are carried. One block without practice: the groups are all
// that is looked at.
TEST(GroupAssignment, ShardsAndTheirMergeHoldTheGroupsOfTheWholeStudy) {
  const Protocol protocol = with_glove(true);
  SimulationOptions options;
  options.participants = 4;
  options.seed = 3;
  options.world = WorldKind::kGraspProxy;
  options.jobs = 2;
  const std::string whole = test::fresh_path("groups_whole.db");
  simulate_study(protocol, whole, options);
  std::vector<std::string> parts;
  for (const std::vector<int>& only : {std::vector<int>{2, 3}, std::vector<int>{0, 1}}) {
    options.only = only;
    parts.push_back(test::fresh_path("groups_part" + std::to_string(only[0]) + ".db"));
    simulate_study(protocol, parts.back(), options);
  }
  const std::string merged = test::fresh_path("groups_merged.db");
  store::merge_studies(parts, merged);
  store::StudyStore a(whole, store::StudyStore::Access::kReadOnly);
  store::StudyStore b(merged, store::StudyStore::Access::kReadOnly);
  const auto people = a.participants();
  ASSERT_EQ(people.size(), 4u);
  std::set<std::string> gloves;
  for (const store::Participant& p : people) {
    ASSERT_EQ(p.between_levels.size(), 2u) << p.id;
    gloves.insert(p.between_levels[0].second);
    EXPECT_EQ(b.participant(p.id)->between_levels, p.between_levels) << p.id;
  }
  EXPECT_EQ(gloves.size(), 2u) << "each run of two enrolments holds both levels";
}

// Every column the exports write is a fixed column, a factor or an item: the names a factor
// or an item may not take are the ones that would be written twice.
TEST(GroupAssignment, ExportHeadersAreTheFixedColumnsTheFactorsAndTheItems) {
  const Protocol protocol = read_protocol(kMixed);
  const std::string path = test::fresh_path("groups_headers.db");
  store::StudyStore::create(path, study_definition(protocol));
  store::StudyStore db(path);
  enrol_participant(db, test::participant("A"));
  std::set<std::string> allowed;
  for (const std::string& c : fixed_export_columns()) allowed.insert(c);
  for (const Factor& f : protocol.factors) allowed.insert(f.name);
  for (const BetweenFactor& f : protocol.between) allowed.insert(f.name);
  for (const QuestionnaireItem& i : protocol.items) allowed.insert(i.id);
  const std::vector<std::function<void(std::ostream&)>> writers = {
      [&](std::ostream& out) { write_trials_csv(db, out); },
      [&](std::ostream& out) { write_questionnaire_csv(db, out); },
      [&](std::ostream& out) { write_frames_csv(db, out); }};
  for (const auto& write : writers) {
    std::ostringstream out;
    write(out);
    std::stringstream header(out.str().substr(0, out.str().find('\n')));
    std::set<std::string> seen;
    for (std::string column; std::getline(header, column, ',');) {
      EXPECT_TRUE(allowed.count(column)) << column;
      EXPECT_TRUE(seen.insert(column).second) << column << " twice";
    }
  }
}

}  // namespace
}  // namespace handlab::studies
