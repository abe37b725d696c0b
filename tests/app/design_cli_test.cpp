// Designs beyond the paper's 2 × 2, as a researcher runs them: each example protocol of
// studies/examples simulated on the grasp proxy, exported, analysed and reported, and its
// completion-time ANOVA equal to R's afex on the same data (tests/data/oracle/designs: the
// study's export and R's numbers, made by afex_design.R as tests/data/oracle/README.md says).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "core/util/json_value.h"
#include "tests/support/cli_runner.h"
#include "tests/support/test_files.h"

namespace handlab {
namespace {

using util::JsonValue;

const std::string kSource = HANDLAB_SOURCE_DIR;
const std::string kOracle = kSource + "/tests/data/oracle/designs/";

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// R writes "NA" where it has no number; we write null.
void expect_same(const JsonValue& mine, const JsonValue& r, const std::string& what) {
  if (r.is_string()) {
    EXPECT_TRUE(mine.is_null()) << what << ": R has none";
    return;
  }
  ASSERT_TRUE(mine.is_number()) << what << ": R has " << r.as_number();
  const double x = mine.as_number(), y = r.as_number();
  EXPECT_LE(std::abs(x - y), 1e-6 * std::max(1.0, std::abs(y))) << what << ": R " << y;
}

struct Example {
  std::string protocol;  // under studies/examples, without ".json"
  int participants;
  int seed;
  int cells;  // of the protocol's factors
};

// Simulates the example, checks its export is the data R analysed, its ANOVA R's, its Tukey
// over every cell of the protocol's factors, and that it reports; returns the study.
std::string simulate_analyse_export_report(const Example& e) {
  const std::string db = test::fresh_path(e.protocol + ".db");
  test::CliResult r =
      test::run_cli("simulate --protocol " + kSource + "/studies/examples/" + e.protocol + ".json" +
                    " --participants " + std::to_string(e.participants) + " --seed " +
                    std::to_string(e.seed) + " --world proxy --jobs 2 --quiet --db " + db);
  EXPECT_EQ(r.status, 0) << r.out;

  const std::string exported = test::fresh_path(e.protocol + "-export");
  r = test::run_cli("export --db " + db + " --out " + exported);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(read(exported + "/trials.csv") == read(kOracle + e.protocol + "_trials.csv"))
      << "the simulated study is not the one R analysed: if the simulation changed on purpose, "
         "make the data and R's numbers again (tests/data/oracle/README.md, designs/)";

  r = test::run_cli("analyze --db " + db + " --json -");
  EXPECT_EQ(r.status, 0) << r.out;
  const JsonValue analysis = JsonValue::parse(r.out);
  const JsonValue& mine = analysis["completion_time"]["anova"];
  const JsonValue oracle = JsonValue::parse(read(kOracle + e.protocol + "_afex.json"));
  EXPECT_EQ(int(oracle["participants"].as_number()), e.participants);
  std::map<std::string, const JsonValue*> by_name;
  for (const JsonValue& effect : mine.as_array()) by_name[effect["effect"].as_string()] = &effect;
  std::size_t compared = 0;
  for (const JsonValue& effect : oracle["effects"].as_array()) {
    const std::string name = effect["effect"].as_string();
    if (name == "(Intercept)") continue;
    ++compared;
    const auto found = by_name.find(name);
    if (found == by_name.end()) {
      ADD_FAILURE() << "no effect " << name;
      continue;
    }
    const JsonValue& m = *found->second;
    for (const auto& [ours, theirs] : std::map<std::string, std::string>{{"df_num", "num_df"},
                                                                         {"df_den", "den_df"},
                                                                         {"ss", "SS"},
                                                                         {"ss_error", "SS_error"},
                                                                         {"mse", "MSE"},
                                                                         {"F", "F"},
                                                                         {"p", "p"},
                                                                         {"pes", "pes"},
                                                                         {"ges", "ges"},
                                                                         {"mauchly_W", "mauchly_W"},
                                                                         {"mauchly_p", "mauchly_p"},
                                                                         {"eps_gg", "GG_eps"},
                                                                         {"eps_hf", "HF_eps_raw"},
                                                                         {"p_gg", "p_GG"},
                                                                         {"p_hf", "p_HF"}})
      expect_same(m[ours], effect[theirs], e.protocol + " " + name + " " + ours);
  }
  EXPECT_EQ(compared, mine.size());

  // What export wrote, analyze --csv reads back to the same ANOVA (the design --db used).
  const JsonValue& design = analysis["completion_time"]["design"];
  std::string within, between;
  for (const JsonValue& f : design["within"].as_array())
    within += (within.empty() ? "" : ",") + f.as_string();
  for (const JsonValue& f : design["between"].as_array())
    between += (between.empty() ? "" : ",") + f.as_string();
  r = test::run_cli("analyze --csv " + exported +
                    "/trials.csv --subject participant --dv completion_time_s --within " + within +
                    (between.empty() ? "" : " --between " + between) + " --json -");
  EXPECT_EQ(r.status, 0) << r.out;
  const JsonValue again = JsonValue::parse(r.out);
  EXPECT_EQ(again["anova"].size(), mine.size());
  for (std::size_t i = 0; i < std::min(mine.size(), again["anova"].size()); ++i)
    for (const char* key : {"effect", "df_num", "df_den", "F", "p", "ges"})
      if (mine[i][key].is_number())  // the same to rounding: cells summed in another order
        expect_same(again["anova"][i][key], mine[i][key],
                    e.protocol + " " + mine[i]["effect"].dump() + " " + key + " from the export");
      else
        EXPECT_EQ(again["anova"][i][key].dump(), mine[i][key].dump()) << e.protocol << " " << key;

  // Tukey over every pair of the protocol's cells.
  std::set<std::string> pairs;
  for (const JsonValue& contrast : analysis["completion_time"]["posthoc"].as_array())
    if (contrast["effect"].as_string() == "strategy:manipulation" && contrast["by"].size() == 0)
      pairs.insert(contrast["contrast"].as_string());
  EXPECT_EQ(int(pairs.size()), e.cells * (e.cells - 1) / 2);

  const std::string report = test::fresh_path(e.protocol + "-report");
  r = test::run_cli("report --db " + db + " --out " + report);
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string html = read(report + "/report.html");
  EXPECT_GT(html.size(), 10000u);
  EXPECT_EQ(read(report + "/report.pdf").rfind("%PDF", 0), 0u);
  return html;
}

TEST(DesignCli, ThreeStrategiesThreeCubesSimulatedAnalysedExportedReportedAsRComputesIt) {
  const std::string html = simulate_analyse_export_report({"three-by-three", 12, 1, 9});
  // Levels as the protocol labels them (those the title does not hold already).
  for (const char* label : {"Even", "Gross", "Medium", "Fine"})
    EXPECT_NE(html.find(label), std::string::npos) << label;
}

// The paper's 2 x 2 within participants, VR experience between them (assigned from the
// participant field): the mixed ANOVA as afex's aov_ez with `between` computes it.
TEST(DesignCli, AMixedDesignSimulatedAnalysedExportedReportedAsRComputesIt) {
  const std::string html = simulate_analyse_export_report({"mixed-vr-experience", 12, 1, 4});
  for (const char* text : {"with Experience (Novice, Experienced; by VR experience) between "
                           "participants",
                           "Experience × Strategy × Manipulation", "Group Experience: "})
    EXPECT_NE(html.find(text), std::string::npos) << text;
}

}  // namespace
}  // namespace handlab
