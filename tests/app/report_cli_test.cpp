// `handlab-cli report` as a researcher runs it, on a study database filled from a shared
// oracle case (R's afex/emmeans/stats results known): every number in the HTML is bound to
// its place in `analyze --db --json` and checked there, the participant-variable ANOVA is
// R's, and the bad inputs (an empty study, one participant, a condition nobody finished, no
// questionnaire) still give a report that says what it could not compute.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "core/store/study_store.h"
#include "core/util/json_value.h"
#include "studies/protocol/protocol.h"
#include "studies/session/session_runner.h"
#include "tests/support/cli_runner.h"
#include "tests/support/test_files.h"

namespace handlab {
namespace {

using util::JsonValue;

const std::string kOracle = std::string(HANDLAB_SOURCE_DIR) + "/tests/data/oracle/studies/";

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::vector<std::string>> csv_rows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(read(path));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct StudyFill {
  int participants = 1000;           // at most this many
  std::string unfinished_condition;  // every trial of it skipped
  bool answers = true;
};

// A study of the paper's protocol whose trials end with the oracle case's times and whose
// last block's questionnaires hold its Likert answers.
std::string oracle_study(const std::string& name, const std::string& label, StudyFill fill = {}) {
  const studies::Protocol protocol = studies::read_protocol(std::string(HANDLAB_SOURCE_DIR) +
                                                            "/studies/fine-manipulation-2021.json");
  const std::string path = test::fresh_path(name);
  store::StudyStore::create(path, studies::study_definition(protocol));
  store::StudyStore store(path);
  const auto times = csv_rows(kOracle + label + "_times.csv");
  const auto likert = csv_rows(kOracle + label + "_likert.csv");
  // participant -> covariates; (participant, manipulation, strategy, repetition) -> time
  std::map<std::string, std::vector<std::string>> people;
  std::map<std::string, double> time_of;
  std::vector<std::string> order;
  for (std::size_t r = 1; r < times.size(); ++r) {
    const auto& t = times[r];
    if (!people.count(t[0])) order.push_back(t[0]);
    people[t[0]] = {t[5], t[6], t[7]};
    time_of[t[0] + "|" + lower(t[1]) + "|" + lower(t[2]) + "|" + t[3]] = std::stod(t[4]);
  }
  std::map<std::string, std::vector<std::string>> answers_of;  // participant|manip|strategy
  for (std::size_t r = 1; r < likert.size(); ++r)
    answers_of[likert[r][0] + "|" + lower(likert[r][1]) + "|" + lower(likert[r][2])] = {
        likert[r][3], likert[r][4], likert[r][5]};
  const auto conditions = protocol.conditions();
  for (std::size_t i = 0; i < order.size() && int(i) < fill.participants; ++i) {
    store::Participant p;
    p.id = order[i];
    p.age = std::stoi(people[p.id][0]);
    p.sex = i % 4 == 0 ? "F" : "M";
    p.handedness = "right";
    p.hand_length = std::stod(people[p.id][1]) / 100.0;
    p.vr_experience = people[p.id][2];
    store.add_participant(p, studies::planned_rows(protocol, p.id, int(i)));
    const std::int64_t session = store.begin_session(p.id, "oracle");
    for (const store::PlannedTrialRow& t : store.plan(p.id)) {
      if (t.practice) continue;
      const studies::Condition& c = conditions[std::size_t(t.condition)];
      const std::string strategy = protocol.factors[0].levels[std::size_t(c.levels[0])].name;
      const std::string manipulation = protocol.factors[1].levels[std::size_t(c.levels[1])].name;
      if (c.label == fill.unfinished_condition) {
        store.skip_trial(p.id, t.position, session, "test: nobody finished it");
        continue;
      }
      const std::int64_t trial = store.begin_trial(t.id, session);
      store::TrialOutcome outcome;
      outcome.success = true;
      outcome.completion_time_s = time_of.at(p.id + "|" + manipulation + "|" + strategy + "|" +
                                             std::to_string(t.repetition));
      if (t.questionnaire && fill.answers) {
        const auto& a = answers_of.at(p.id + "|" + manipulation + "|" + strategy);
        outcome.answers = {{"precision", std::stoi(a[0])},
                           {"ease", std::stoi(a[1])},
                           {"naturalness", std::stoi(a[2])}};
      }
      store.finish_trial(trial, outcome);
    }
    store.end_session(session, "finished");
  }
  return path;
}

// A JSON pointer ("/completion_time/anova/2/F"), or two joined by '*' (their product).
std::optional<double> resolve(const JsonValue& root, const std::string& source) {
  const std::size_t star = source.find('*');
  if (star != std::string::npos) {
    const auto a = resolve(root, source.substr(0, star));
    const auto b = resolve(root, source.substr(star + 1));
    if (!a || !b) return std::nullopt;
    return *a * *b;
  }
  const JsonValue* at = &root;
  std::stringstream parts(source.substr(1));
  for (std::string part; std::getline(parts, part, '/');) {
    if (at->is_array())
      at = &(*at)[std::size_t(std::stoul(part))];
    else
      at = &(*at)[part];
  }
  if (at->is_null()) return std::nullopt;
  return at->as_number();
}

struct Bound {
  std::string source, relation, text;
};

std::vector<Bound> bound_numbers(const std::string& html) {
  std::vector<Bound> out;
  const std::regex span(
      R"re(<span class="n" data-src="([^"]+)"(?: data-rel="(&lt;|&gt;)")?>([^<]*)</span>)re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), span); it != std::sregex_iterator();
       ++it)
    out.push_back({(*it)[1], (*it)[2], (*it)[3]});
  return out;
}

// Checks each bound number against the analysis; returns how many were checked.
int check_against(const std::string& html, const JsonValue& analysis) {
  int checked = 0;
  for (const Bound& b : bound_numbers(html)) {
    const std::optional<double> value = resolve(analysis, b.source);
    if (b.text == "NA") {
      EXPECT_FALSE(value && std::isfinite(*value)) << b.source;
      continue;
    }
    EXPECT_TRUE(value) << b.source << " is not in the analysis JSON";
    if (!value) continue;
    const double shown = std::stod(b.text.front() == '.'        ? "0" + b.text
                                   : b.text.rfind("-.", 0) == 0 ? "-0" + b.text.substr(1)
                                                                : b.text);
    const std::size_t dot = b.text.find('.');
    const int decimals = dot == std::string::npos ? 0 : int(b.text.size() - dot - 1);
    const double half_unit = 0.5 * std::pow(10.0, -decimals) + 1e-9;
    if (b.relation == "&lt;")
      EXPECT_LT(*value, shown) << b.source;
    else if (b.relation == "&gt;")
      EXPECT_GT(*value, shown) << b.source;
    else
      EXPECT_LE(std::abs(*value - shown), half_unit) << b.source << " shows " << b.text;
    ++checked;
  }
  return checked;
}

TEST(ReportCli, EveryNumberInTheHtmlIsTheAnalysisJsons) {
  const std::string db = oracle_study("report_oracle.db", "study_n20_s101");
  const std::string json = test::fresh_path("report_oracle.json");
  test::CliResult r = test::run_cli("analyze --db " + db + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  const JsonValue analysis = JsonValue::parse(read(json));
  const std::string out = test::fresh_path("report_oracle");
  r = test::run_cli("report --db " + db + " --out " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("not computed"), std::string::npos) << r.out;
  const std::string html = read(out + "/report.html");

  const int checked = check_against(html, analysis);
  EXPECT_GT(checked, 300);
  // Every table's number column holds bound numbers only.
  const std::regex numeric_cell(R"re(<td class="num">(.*?)</td>)re");
  const std::regex span(R"re(<span[^>]*>[^<]*</span>)re");
  int cells = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), numeric_cell);
       it != std::sregex_iterator(); ++it, ++cells) {
    const std::string rest = std::regex_replace(std::string((*it)[1]), span, "");
    EXPECT_EQ(rest.find_first_of("0123456789"), std::string::npos) << (*it)[1];
  }
  EXPECT_GT(cells, 200);
  // Levels as the protocol names them, not R's X1.
  EXPECT_EQ(html.find("X1"), std::string::npos);
  // The paper's schedule: nothing before the five blocks.
  EXPECT_NE(html.find("for each participant and block, with no practice trials."),
            std::string::npos);
  // The four figures, inline.
  int figures = 0;
  for (std::size_t at = html.find("<figure"); at != std::string::npos;
       at = html.find("<figure", at + 1))
    figures += html.compare(html.find('>', at) + 2, 4, "<svg") == 0 ? 1 : 0;
  EXPECT_EQ(figures, 4);
  // The PDF: pages as reported.
  const std::string pdf = read(out + "/report.pdf");
  EXPECT_EQ(pdf.rfind("%PDF", 0), 0u);
  std::smatch pages;
  ASSERT_TRUE(std::regex_search(r.out, pages, std::regex(R"(\((\d+) pages\))")));
  int page_objects = 0;
  for (std::size_t at = pdf.find("/Type /Page\n"); at != std::string::npos;
       at = pdf.find("/Type /Page\n", at + 1))
    ++page_objects;
  EXPECT_EQ(page_objects, std::stoi(pages[1]));
  EXPECT_GE(page_objects, 4);
}

TEST(ReportCli, TheParticipantVariablesAnovaIsRs) {
  const std::string db = oracle_study("report_covariates.db", "study_n20_s101");
  const std::string json = test::fresh_path("report_covariates.json");
  const test::CliResult r = test::run_cli("analyze --db " + db + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("With hand_length as a covariate"), std::string::npos) << r.out;
  const JsonValue mine = JsonValue::parse(read(json))["participant_variables"];
  const JsonValue oracle =
      JsonValue::parse(read(kOracle + "study_n20_s101.json"))["covariate_analyses"];
  const std::map<std::string, std::string> names = {
      {"age", "age__MS"}, {"hand_length", "hand_size__MS"}, {"vr_experience", "vr_experience__MS"}};
  ASSERT_EQ(mine.size(), 3u);
  for (std::size_t v = 0; v < mine.size(); ++v) {
    const std::string variable = mine[v]["variable"].as_string();
    const JsonValue& r_table = oracle[names.at(variable)]["afex_tables"]["none"]["table"];
    const JsonValue& anova = mine[v]["analysis"]["anova"];
    ASSERT_EQ(anova.size(), r_table.size()) << variable;
    int compared = 0;
    for (std::size_t i = 0; i < r_table.size(); ++i) {
      // R names hand_size what the study stores as hand_length; factor order may differ.
      std::string effect = r_table[i]["effect"].as_string();
      effect = std::regex_replace(effect, std::regex("hand_size"), "hand_length");
      std::vector<std::string> parts;
      std::stringstream s(effect);
      for (std::string part; std::getline(s, part, ':');) parts.push_back(part);
      std::sort(parts.begin(), parts.end());
      for (std::size_t j = 0; j < anova.size(); ++j) {
        std::vector<std::string> own;
        std::stringstream t(anova[j]["effect"].as_string());
        for (std::string part; std::getline(t, part, ':');) own.push_back(part);
        std::sort(own.begin(), own.end());
        if (own != parts) continue;
        EXPECT_NEAR(anova[j]["F"].as_number(), r_table[i]["F"].as_number(),
                    1e-6 * std::max(1.0, r_table[i]["F"].as_number()))
            << variable << " " << effect;
        EXPECT_NEAR(anova[j]["p"].as_number(), r_table[i]["p"].as_number(), 1e-6)
            << variable << " " << effect;
        ++compared;
      }
    }
    EXPECT_EQ(compared, int(r_table.size())) << variable;
  }
}

TEST(ReportCli, BadInputsStillGiveAReportThatSaysWhatIsMissing) {
  struct Case {
    std::string name, expected;
    StudyFill fill;
  };
  const std::vector<Case> cases = {
      {"empty", "no scheduled trial has a completion time yet", {0, "", true}},
      {"one", "fewer than two participants", {1, "", true}},
      {"unfinished", "condition ours-fine has no completion time yet", {6, "ours-fine", true}},
      {"unasked", "no questionnaire has been answered yet", {6, "", false}},
  };
  for (const Case& c : cases) {
    const std::string db = oracle_study("report_bad_" + c.name + ".db", "study_n20_s101", c.fill);
    const std::string out = test::fresh_path("report_bad_" + c.name);
    const test::CliResult r = test::run_cli("report --db " + db + " --out " + out);
    ASSERT_EQ(r.status, 0) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find("not computed"), std::string::npos) << c.name << ": " << r.out;
    const std::string html = read(out + "/report.html");
    EXPECT_NE(html.find(c.expected), std::string::npos) << c.name;
    EXPECT_EQ(read(out + "/report.pdf").rfind("%PDF", 0), 0u) << c.name;
    // Whatever was computed agrees with the analysis.
    const std::string json = out + "/analysis.json";
    ASSERT_EQ(test::run_cli("analyze --db " + db + " --json " + json).status, 0) << c.name;
    check_against(html, JsonValue::parse(read(json)));
  }
}

}  // namespace
}  // namespace handlab
