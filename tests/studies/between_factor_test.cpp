// Between-participants factors: read from the protocol with refusals that name the field,
// assigned at enrolment (balanced in order of enrolment, or from a participant field), stored
// with the participant, exported beside the fields and shown in the protocol's summary.
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "studies/export/study_export.h"
#include "studies/session/enrolment.h"
#include "studies/session/group_assignment.h"
#include "studies/session/session_runner.h"
#include "tests/support/test_files.h"
#include "tests/support/test_participant.h"

namespace handlab::studies {
namespace {

const std::string kMixed =
    std::string(HANDLAB_SOURCE_DIR) + "/studies/examples/mixed-vr-experience.json";

std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

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
  person.age = 17;
  EXPECT_THROW(assign_groups(p, person, 0), std::invalid_argument);
  const auto problems = participant_problems(person, {}, &p);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "age");
  EXPECT_NE(problems[0].message.find("The age 17 is in no level of the between factor age_group"),
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
            "novice (none), experienced (some, yes, expert); from vr_experience");
  EXPECT_EQ(summary["Factor strategy"], "naive, ours");  // labels that say their method
}

}  // namespace
}  // namespace handlab::studies
