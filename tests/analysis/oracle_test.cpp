// Every number the statistics issue asks for, against R (afex 1.2, emmeans 1.8, stats) on
// every case under tests/data/oracle (a copy of the R reference results).
#include <map>

#include <gtest/gtest.h>

#include "analysis/data/long_table.h"
#include "analysis/report/study_analysis.h"
#include "analysis/stats/posthoc.h"
#include "analysis/stats/rm_anova.h"
#include "oracle_support.h"

namespace handlab {
namespace {

using testing::expect_r;
using testing::r_number;
using testing::Tolerance;
using util::JsonValue;

std::vector<std::string> strings(const JsonValue& v) {
  std::vector<std::string> out;
  if (v.is_string()) {
    if (v.as_string() != "NA") out.push_back(v.as_string());
    return out;
  }
  for (const auto& item : v.as_array()) out.push_back(item.as_string());
  return out;
}

// Compares the univariate effects table (car's summary, with afex's es and corrections).
void expect_effects(const stats::AnovaResult& mine, const JsonValue& effects,
                    const std::string& label) {
  std::map<std::string, const stats::AnovaEffect*> by_name;
  by_name["(Intercept)"] = &mine.intercept;
  for (const auto& e : mine.effects) by_name[e.effect] = &e;
  ASSERT_EQ(mine.effects.size() + 1, effects.size()) << label;
  for (std::size_t i = 0; i < effects.size(); ++i) {
    const JsonValue& r = effects[i];
    const std::string name = r["effect"].as_string();
    if (i > 0) {
      EXPECT_EQ(mine.effects[i - 1].effect, name) << label << ": afex's effect order";
    }
    ASSERT_TRUE(by_name.count(name)) << label << ": no effect " << name;
    const stats::AnovaEffect& e = *by_name[name];
    const std::string what = label + " " + name + " ";
    expect_r(e.df_num, r["num_df"], what + "num df");
    expect_r(e.df_den, r["den_df"], what + "den df");
    expect_r(e.ss, r["SS"], what + "SS");
    expect_r(e.ss_error, r["SS_error"], what + "error SS");
    expect_r(e.mse, r["MSE"], what + "MSE");
    expect_r(e.f, r["F"], what + "F");
    expect_r(e.p, r["p"], what + "p", Tolerance::kP);
    if (name == "(Intercept)") continue;
    expect_r(e.pes, r["pes"], what + "pes");
    expect_r(e.ges, r["ges"], what + "ges");
    if (std::isnan(r_number(r["GG_eps"]))) {
      EXPECT_TRUE(std::isnan(e.eps_gg)) << what << "has no sphericity test in R";
      continue;
    }
    expect_r(e.eps_gg, r["GG_eps"], what + "GG epsilon");
    expect_r(e.eps_hf, r["HF_eps_raw"], what + "HF epsilon");
    expect_r(e.p_gg, r["p_GG"], what + "p GG", Tolerance::kP);
    expect_r(e.p_hf, r["p_HF"], what + "p HF", Tolerance::kP);
    expect_r(e.mauchly_w, r["mauchly_W"], what + "Mauchly W");
    expect_r(e.mauchly_p, r["mauchly_p"], what + "Mauchly p", Tolerance::kP);
  }
}

// afex's own tables (none / GG / HF corrections): df, MSE, F, p as afex prints them.
void expect_afex_tables(const stats::AnovaResult& mine, const JsonValue& tables,
                        const std::string& label) {
  for (const char* correction : {"none", "GG", "HF"}) {
    const JsonValue& table = tables[correction]["table"];
    ASSERT_EQ(table.size(), mine.effects.size());
    for (std::size_t i = 0; i < table.size(); ++i) {
      const stats::AnovaEffect& e = mine.effects[i];
      const JsonValue& r = table[i];
      double eps = 1.0, p = e.p;
      if (!std::isnan(e.eps_gg) && std::string(correction) == "GG") eps = e.eps_gg, p = e.p_gg;
      if (!std::isnan(e.eps_gg) && std::string(correction) == "HF")
        eps = std::min(1.0, e.eps_hf), p = e.p_hf;
      const std::string what = label + " afex " + correction + " " + e.effect + " ";
      expect_r(e.df_num * eps, r["num_df"], what + "num df");
      expect_r(e.df_den * eps, r["den_df"], what + "den df");
      expect_r(e.ss_error / (e.df_den * eps), r["MSE"], what + "MSE");
      expect_r(e.f, r["F"], what + "F");
      expect_r(p, r["p"], what + "p", Tolerance::kP);
      expect_r(e.ges, r["ges"], what + "ges");
    }
  }
}

std::string by_label(const std::vector<std::pair<std::string, std::string>>& at) {
  std::string s;
  for (const auto& [f, l] : at) s += f + "=" + stats::emmeans_level_label(l) + ";";
  return s;
}

// emmeans on the multivariate model: cell means and pairs with every adjustment R gave.
void expect_emmeans(const stats::RmData& data, const std::string& spec_text, const JsonValue& r,
                    const std::string& label) {
  const stats::PosthocResult mine =
      stats::pairwise_comparisons(data, stats::PosthocSpec::parse(spec_text, data));
  const stats::PosthocSpec spec = stats::PosthocSpec::parse(spec_text, data);
  // Cell means, matched by their factor levels.
  std::map<std::string, const stats::MarginalMean*> means;
  for (const auto& m : mine.means) means[by_label(m.at)] = &m;
  ASSERT_EQ(r["cell_means"].size(), mine.means.size()) << label;
  for (const auto& cell : r["cell_means"].as_array()) {
    std::string key;
    for (const auto& f : spec.factors)
      key += f + "=" + stats::emmeans_level_label(cell[f].as_string()) + ";";
    for (const auto& f : spec.by)
      key += f + "=" + stats::emmeans_level_label(cell[f].as_string()) + ";";
    ASSERT_TRUE(means.count(key)) << label << " no cell " << key;
    const auto& m = *means[key];
    expect_r(m.estimate, cell["emmean"], label + " emmean " + key);
    expect_r(m.se, cell["SE"], label + " SE " + key);
    expect_r(m.df, cell["df"], label + " df " + key);
    expect_r(m.lower_cl, cell["lower_CL"], label + " lower CL " + key);
    expect_r(m.upper_cl, cell["upper_CL"], label + " upper CL " + key);
  }
  // Pairs, matched by label and by-group; R's level order may differ (alphabetical), so a
  // reversed pair counts with its sign flipped.
  auto find_pair = [&](const JsonValue& pair, double* sign) -> const stats::PairwiseContrast* {
    std::string by;
    for (const auto& f : spec.by) by += f + "=" + pair[f].as_string() + ";";
    const std::string contrast = pair["contrast"].as_string();
    const auto dash = contrast.find(" - ");
    const std::string reversed = contrast.substr(dash + 3) + " - " + contrast.substr(0, dash);
    for (const auto& c : mine.contrasts) {
      if (by_label(c.by) != by) continue;
      if (c.contrast == contrast) return *sign = 1.0, &c;
      if (c.contrast == reversed) return *sign = -1.0, &c;
    }
    return nullptr;
  };
  struct Column {
    const char* key;
    double stats::PairwiseContrast::*p;
    Tolerance tolerance;
  };
  for (const Column& column :
       {Column{"pairs_none", &stats::PairwiseContrast::p_none, Tolerance::kP},
        Column{"pairs_tukey", &stats::PairwiseContrast::p_tukey, Tolerance::kTukeyP},
        Column{"pairs_bonferroni", &stats::PairwiseContrast::p_bonferroni, Tolerance::kP},
        Column{"pairs_bonferroni_family_all_by_groups", &stats::PairwiseContrast::p_bonferroni_all,
               Tolerance::kP},
        Column{"pairs_holm_family_all_by_groups", &stats::PairwiseContrast::p_holm_all,
               Tolerance::kP}}) {
    const JsonValue* pairs = r.find(column.key);
    if (!pairs) continue;
    ASSERT_EQ(pairs->size(), mine.contrasts.size()) << label << " " << column.key;
    for (const auto& pair : pairs->as_array()) {
      double sign = 1.0;
      const stats::PairwiseContrast* c = find_pair(pair, &sign);
      ASSERT_NE(c, nullptr) << label << " no contrast " << pair["contrast"].as_string();
      const std::string what = label + " " + column.key + " " + pair["contrast"].as_string() + " ";
      expect_r(sign * c->estimate, pair["estimate"], what + "estimate");
      expect_r(c->se, pair["SE"], what + "SE");
      expect_r(c->df, pair["df"], what + "df");
      expect_r(sign * c->t, pair["t_ratio"], what + "t");
      expect_r(c->*column.p, pair["p"], what + "p", column.tolerance);
    }
  }
}

stats::RmData prepare(const analysis::LongTable& table, const std::string& subject,
                      const std::string& dv, std::vector<std::string> within,
                      std::vector<std::string> between = {},
                      std::vector<std::string> covariates = {},
                      std::vector<std::string> observed = {}) {
  return stats::prepare_rm_data(table, {subject, dv, std::move(within), std::move(between),
                                        std::move(covariates), std::move(observed)});
}

class StudyOracle : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    name_ = GetParam();
    oracle_ = testing::read_json(testing::oracle_path("studies/" + name_ + ".json"));
    times_ = std::make_unique<analysis::LongTable>(
        analysis::LongTable::read_csv(testing::oracle_path("studies/" + name_ + "_times.csv")));
  }
  std::string name_;
  JsonValue oracle_;
  std::unique_ptr<analysis::LongTable> times_;
};

TEST_P(StudyOracle, RepeatedMeasuresAnova) {
  const auto data =
      prepare(*times_, "participant", "time", {"manipulation", "strategy", "repetition"});
  EXPECT_EQ(data.dropped_subjects, strings(oracle_["rm_anova"]["participants_dropped"]));
  EXPECT_EQ(int(data.subjects.size()), int(r_number(oracle_["rm_anova"]["n_used"])));
  if (!data.dropped_subjects.empty()) {
    ASSERT_EQ(data.warnings.size(), 1u);
    EXPECT_NE(data.warnings[0].find(data.dropped_subjects[0]), std::string::npos);
  }
  const auto anova = stats::rm_anova(data);
  expect_effects(anova, oracle_["rm_anova"]["effects"], name_);
  expect_afex_tables(anova, oracle_["rm_anova"]["afex_tables"], name_);
}

TEST_P(StudyOracle, PostHocOnTheMultivariateModel) {
  const auto data =
      prepare(*times_, "participant", "time", {"manipulation", "strategy", "repetition"});
  const std::map<std::string, std::string> specs = {
      {"MS_cells", "manipulation:strategy"},
      {"strategy_by_repetition", "strategy|repetition"},
      {"strategy_by_manipulation_repetition", "strategy|manipulation:repetition"},
      {"strategy_by_manipulation", "strategy|manipulation"},
      {"manipulation_by_strategy", "manipulation|strategy"},
      {"repetition", "repetition"}};
  for (const auto& [key, spec] : specs)
    expect_emmeans(data, spec, oracle_["emmeans"][key]["multivariate"], name_ + " " + key);
}

TEST_P(StudyOracle, PairedTTestsEqualTheMultivariatePostHoc) {
  const auto data =
      prepare(*times_, "participant", "time", {"manipulation", "strategy", "repetition"});
  const auto mine =
      stats::pairwise_comparisons(data, stats::PosthocSpec::parse("manipulation:strategy", data));
  const JsonValue& pairs = oracle_["paired_t_MS_cells"]["pairs"];
  ASSERT_EQ(pairs.size(), mine.contrasts.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(mine.contrasts[i].contrast, pairs[i]["contrast"].as_string());
    expect_r(mine.contrasts[i].t, pairs[i]["t"], name_ + " paired t");
    expect_r(mine.contrasts[i].p_none, pairs[i]["p_raw"], name_ + " paired p", Tolerance::kP);
    expect_r(mine.contrasts[i].p_tukey, pairs[i]["p_tukey_ptukey"], name_ + " ptukey",
             Tolerance::kTukeyP);
    expect_r(mine.contrasts[i].p_bonferroni, pairs[i]["p_bonferroni"], name_ + " Bonferroni",
             Tolerance::kP);
  }
}

TEST_P(StudyOracle, CovariateAndBetweenSubjectAnalyses) {
  int checked = 0;
  for (const auto& [key, analysis] : oracle_["covariate_analyses"].as_object()) {
    if (!analysis.is_object() || !analysis.find("effects")) continue;
    const auto data = prepare(*times_, "participant", "time", strings(analysis["within"]),
                              strings(analysis["between"]), strings(analysis["covariate"]));
    EXPECT_EQ(int(data.subjects.size()), int(r_number(analysis["n_used"]))) << key;
    for (std::size_t k = 0; k < data.covariates.size(); ++k)
      expect_r(data.covariate_means[k], analysis["centering_means"][data.covariates[k]],
               name_ + " " + key + " centring");
    const auto anova = stats::rm_anova(data);
    expect_effects(anova, analysis["effects"], name_ + " " + key);
    expect_afex_tables(anova, analysis["afex_tables"], name_ + " " + key);
    // Generalised eta squared with the covariates and between factors declared observed.
    if (const JsonValue* observed = analysis.find("ges_with_observed")) {
      const auto with_observed = stats::rm_anova(prepare(
          *times_, "participant", "time", strings(analysis["within"]), strings(analysis["between"]),
          strings(analysis["covariate"]), strings((*observed)["observed"])));
      const JsonValue& table = (*observed)["table"];
      ASSERT_EQ(table.size(), with_observed.effects.size());
      for (std::size_t i = 0; i < table.size(); ++i) {
        EXPECT_EQ(with_observed.effects[i].effect, table[i]["effect"].as_string());
        expect_r(with_observed.effects[i].ges, table[i]["ges"],
                 name_ + " " + key + " ges observed");
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

TEST_P(StudyOracle, DescriptivesPerCell) {
  analysis::AnalysisRequest request;
  request.design = {"participant", "time", {"manipulation", "strategy", "repetition"}, {}, {}, {}};
  request.posthoc = {"manipulation:strategy"};
  const auto report = analysis::run_analysis(*times_, request);
  const JsonValue& cells = oracle_["descriptives"]["cells_MSR"];
  ASSERT_EQ(cells.size(), report.descriptives.size());
  for (const auto& r : cells.as_array()) {
    const analysis::CellDescriptives* found = nullptr;
    for (const auto& c : report.descriptives)
      if (c.cell[0].second == r["manipulation"].as_string() &&
          c.cell[1].second == r["strategy"].as_string() &&
          c.cell[2].second == r["repetition"].as_string())
        found = &c;
    ASSERT_NE(found, nullptr);
    const std::string what = name_ + " descriptives ";
    expect_r(found->d.n, r["n"], what + "n");
    expect_r(found->d.mean, r["mean"], what + "mean");
    expect_r(found->d.sd, r["sd"], what + "sd");
    expect_r(found->d.se, r["se"], what + "se");
    expect_r(found->d.median, r["median"], what + "median");
    expect_r(found->d.q1, r["q1_type7"], what + "q1");
    expect_r(found->d.q3, r["q3_type7"], what + "q3");
    expect_r(found->d.min, r["min"], what + "min");
    expect_r(found->d.max, r["max"], what + "max");
  }
  // Over participant means across repetitions (fun_aggregate = mean), every participant.
  request.design.within = {"manipulation", "strategy"};
  const auto ms = analysis::run_analysis(*times_, request);
  const JsonValue& ms_cells = oracle_["descriptives"]["cells_MS_participant_means_all"];
  ASSERT_EQ(ms_cells.size(), ms.descriptives.size());
  for (const auto& r : ms_cells.as_array()) {
    for (const auto& c : ms.descriptives) {
      if (c.cell[0].second != r["manipulation"].as_string() ||
          c.cell[1].second != r["strategy"].as_string())
        continue;
      expect_r(c.d.n, r["n"], name_ + " MS n");
      expect_r(c.d.mean, r["mean"], name_ + " MS mean");
      expect_r(c.d.sd, r["sd"], name_ + " MS sd");
      expect_r(c.d.median, r["median"], name_ + " MS median");
    }
  }
}

TEST_P(StudyOracle, FriedmanAndWilcoxonOnTheQuestionnaire) {
  const auto likert =
      analysis::LongTable::read_csv(testing::oracle_path("studies/" + name_ + "_likert.csv"));
  analysis::AnalysisRequest request;
  request.design.subject = "participant";
  request.design.within = {"manipulation", "strategy"};
  for (const auto& [item, r] : oracle_["likert"]["items"].as_object())
    request.nonparametric_items.push_back(item);
  const auto report = analysis::run_analysis(likert, request);
  std::size_t w = 0;
  for (std::size_t i = 0; i < report.friedman.size(); ++i) {
    const auto& f = report.friedman[i];
    const JsonValue& r = oracle_["likert"]["items"][f.dv];
    const std::string what = name_ + " " + f.dv + " ";
    expect_r(f.result.chisq, r["friedman"]["statistic"], what + "Friedman chi2");
    expect_r(f.result.df, r["friedman"]["df"], what + "Friedman df");
    expect_r(f.result.p, r["friedman"]["p"], what + "Friedman p", Tolerance::kP);
    expect_r(f.result.kendall_w, r["friedman"]["kendall_W"], what + "Kendall W");
    expect_r(f.result.n, r["friedman"]["n_blocks"], what + "Friedman n");
    EXPECT_EQ(f.dropped_subjects, strings(r["friedman"]["participants_dropped"]));
    for (const auto& pair : r["wilcoxon_pairs"].as_array()) {
      ASSERT_LT(w, report.wilcoxon.size());
      const auto& mine = report.wilcoxon[w++];
      std::string expected = pair["pair"].as_string();
      for (auto at = expected.find('-'); at != std::string::npos; at = expected.find('-', at + 1))
        expected[at] = ' ';
      expected.replace(expected.find(" vs "), 4, " - ");
      EXPECT_EQ(mine.contrast, expected);
      expect_r(mine.result.v, pair["V"], what + mine.contrast + " V");
      expect_r(mine.result.n, pair["n_nonzero"], what + mine.contrast + " n");
      EXPECT_EQ(mine.result.exact, pair["exact_used"].as_bool()) << what << mine.contrast;
      expect_r(mine.result.p, pair["p"], what + mine.contrast + " p", Tolerance::kP);
      expect_r(mine.p_bonferroni, pair["p_bonferroni"], what + mine.contrast + " Bonferroni",
               Tolerance::kP);
    }
  }
  EXPECT_EQ(w, report.wilcoxon.size());
}

INSTANTIATE_TEST_SUITE_P(Studies, StudyOracle,
                         ::testing::Values("study_n20_s101", "study_n57_s303_odd",
                                           "study_n13_s404_zero_likert",
                                           "study_n20_s606_missing_cell",
                                           "study_n10_s707_slider_exact"));

TEST(AfexReference, MaxwellDelaney12_1) {
  const JsonValue oracle = testing::read_json(testing::oracle_path("ref/afex_md_12.1.json"));
  const auto table = analysis::LongTable::read_csv(testing::oracle_path("ref/afex_md_12.1.csv"));
  const auto data = prepare(table, "id", "rt", {"angle", "noise"});
  const auto anova = stats::rm_anova(data);
  expect_effects(anova, oracle["anova"]["effects"], "md_12.1");
  expect_afex_tables(anova, oracle["anova"]["afex_tables"], "md_12.1");
  expect_emmeans(data, "angle:noise", oracle["emmeans"]["multivariate"], "md_12.1");
  // The published values (Maxwell & Delaney Table 12.5).
  const JsonValue& published = oracle["published"];
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(anova.effects[i].ss, published["SS"][i].as_number(), 1e-6);
    EXPECT_NEAR(anova.effects[i].f, published["F"][i].as_number(), 0.005);
  }
}

TEST(AfexReference, OBrienKaiserMixedDesignWithObservedGender) {
  const JsonValue oracle = testing::read_json(testing::oracle_path("ref/afex_obk.long.json"));
  const auto table = analysis::LongTable::read_csv(testing::oracle_path("ref/afex_obk.long.csv"));
  const auto data =
      prepare(table, "id", "value", {"phase", "hour"}, {"treatment", "gender"}, {}, {"gender"});
  const auto anova = stats::rm_anova(data);
  expect_effects(anova, oracle["anova"]["effects"], "obk.long");
  expect_afex_tables(anova, oracle["anova"]["afex_tables"], "obk.long");
  expect_emmeans(data, "phase", oracle["emmeans"]["multivariate"], "obk.long");
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(anova.effects[i].f, oracle["published"]["F"][i].as_number(), 0.005);
}

}  // namespace
}  // namespace handlab
