// handlab against R on cases made by tests/data/r/make_reference.R: an unbalanced mixed
// design with a covariate, and a 4 x 3 within design with replicates to average.
#include <map>

#include <gtest/gtest.h>

#include "analysis/data/long_table.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "oracle_support.h"

namespace handlab {
namespace {

using testing::expect_r;
using testing::Tolerance;
using util::JsonValue;

std::string r_case(const std::string& file) {
  return std::string(HANDLAB_SOURCE_DIR) + "/tests/data/r/" + file;
}

void expect_effects(const stats::AnovaResult& mine, const JsonValue& effects) {
  ASSERT_EQ(effects.size(), mine.effects.size() + 1);
  for (std::size_t i = 0; i < effects.size(); ++i) {
    const JsonValue& r = effects[i];
    const stats::AnovaEffect& e = i == 0 ? mine.intercept : mine.effects[i - 1];
    const std::string what = r["effect"].as_string() + " ";
    EXPECT_EQ(e.effect, r["effect"].as_string());
    expect_r(e.df_num, r["num_df"], what + "num df");
    expect_r(e.df_den, r["den_df"], what + "den df");
    expect_r(e.ss, r["SS"], what + "SS");
    expect_r(e.ss_error, r["SS_error"], what + "error SS");
    expect_r(e.f, r["F"], what + "F");
    expect_r(e.p, r["p"], what + "p", Tolerance::kP);
    if (const JsonValue* pes = r.find("pes")) expect_r(e.pes, *pes, what + "pes");
    if (const JsonValue* ges = r.find("ges")) expect_r(e.ges, *ges, what + "ges");
    if (const JsonValue* gg = r.find("GG_eps")) {
      expect_r(e.eps_gg, *gg, what + "GG eps");
      expect_r(e.eps_hf, r["HF_eps_raw"], what + "HF eps");
      expect_r(e.p_gg, r["p_GG"], what + "p GG", Tolerance::kP);
      expect_r(e.p_hf, r["p_HF"], what + "p HF", Tolerance::kP);
      expect_r(e.mauchly_w, r["mauchly_W"], what + "Mauchly W");
      expect_r(e.mauchly_p, r["mauchly_p"], what + "Mauchly p", Tolerance::kP);
    } else {
      EXPECT_TRUE(std::isnan(e.eps_gg)) << what;
    }
  }
}

void expect_pairs(const stats::PosthocResult& mine, const JsonValue& r,
                  const std::vector<std::string>& by) {
  for (const auto& [adjust, field] :
       std::vector<std::pair<std::string, double stats::PairwiseContrast::*>>{
           {"none", &stats::PairwiseContrast::p_none},
           {"tukey", &stats::PairwiseContrast::p_tukey},
           {"bonferroni", &stats::PairwiseContrast::p_bonferroni},
           {"holm", &stats::PairwiseContrast::p_holm}}) {
    const JsonValue& pairs = r[adjust];
    ASSERT_EQ(pairs.size(), mine.contrasts.size()) << adjust;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto& c = mine.contrasts[i];
      const std::string what = adjust + " " + pairs[i]["contrast"].as_string() + " ";
      EXPECT_EQ(c.contrast, pairs[i]["contrast"].as_string());
      for (std::size_t b = 0; b < by.size(); ++b)
        EXPECT_EQ(c.by[b].second, pairs[i][by[b]].as_string());
      expect_r(c.estimate, pairs[i]["estimate"], what + "estimate");
      expect_r(c.se, pairs[i]["SE"], what + "SE");
      expect_r(c.df, pairs[i]["df"], what + "df");
      expect_r(c.t, pairs[i]["t"], what + "t");
      expect_r(c.*field, pairs[i]["p"], what + "p",
               adjust == "tukey" ? Tolerance::kTukeyP : Tolerance::kP);
    }
  }
}

TEST(RReference, UnbalancedMixedDesignWithCovariate) {
  const JsonValue r = testing::read_json(r_case("mixed_unbalanced_covariate.json"));
  const auto table = analysis::LongTable::read_csv(r_case("mixed_unbalanced_covariate.csv"));
  const auto data = stats::prepare_rm_data(table, {"id", "y", {"A", "B"}, {"G"}, {"age"}, {}});
  expect_effects(stats::rm_anova(data), r["effects"]);
  expect_pairs(stats::pairwise_comparisons(data, stats::PosthocSpec::parse("A", data)),
               r["emmeans_A"], {});
  expect_pairs(stats::pairwise_comparisons(data, stats::PosthocSpec::parse("B|A", data)),
               r["emmeans_B_by_A"], {"A"});
}

TEST(RReference, WithinDesignWithReplicatesAveraged) {
  const JsonValue r = testing::read_json(r_case("within_4x3_replicates.json"));
  const auto table = analysis::LongTable::read_csv(r_case("within_4x3_replicates.csv"));
  const auto data = stats::prepare_rm_data(table, {"id", "y", {"C", "D"}, {}, {}, {}});
  ASSERT_EQ(data.warnings.size(), 1u);
  EXPECT_NE(data.warnings[0].find("mean"), std::string::npos);
  expect_effects(stats::rm_anova(data), r["effects"]);
  expect_pairs(stats::pairwise_comparisons(data, stats::PosthocSpec::parse("C:D", data)),
               r["emmeans_CD"], {});
  expect_pairs(stats::pairwise_comparisons(data, stats::PosthocSpec::parse("C|D", data)),
               r["emmeans_C_by_D"], {"D"});
}

}  // namespace
}  // namespace handlab
