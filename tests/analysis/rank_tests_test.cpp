// Rank tests and p adjustment against the examples in R's help pages (values computed by
// R 4.2 and published by Hollander & Wolfe 1973).
#include <gtest/gtest.h>

#include "analysis/data/long_table.h"
#include "analysis/stats/nonparametric.h"
#include "analysis/stats/p_adjust.h"
#include "analysis/stats/ptukey.h"
#include "oracle_support.h"

namespace handlab::stats {
namespace {

using handlab::testing::expect_r;
using handlab::testing::oracle_path;
using handlab::testing::read_json;
using handlab::testing::Tolerance;

TEST(Friedman, RoundingTimes) {
  const auto table = analysis::LongTable::read_csv(oracle_path("ref/friedman_roundingtimes.csv"));
  const auto a = table.numbers("round_out"), b = table.numbers("narrow_angle"),
             c = table.numbers("wide_angle");
  Eigen::MatrixXd m(Eigen::Index(a.size()), 3);
  for (std::size_t i = 0; i < a.size(); ++i) m.row(Eigen::Index(i)) << a[i], b[i], c[i];
  const FriedmanResult r = friedman_test(m);
  const auto oracle = read_json(oracle_path("ref/friedman_roundingtimes.json"));
  expect_r(r.chisq, oracle["RoundingTimes"]["statistic"], "chi2");
  expect_r(r.p, oracle["RoundingTimes"]["p"], "p", Tolerance::kP);
  EXPECT_EQ(r.df, 2);
  EXPECT_EQ(r.rank_sums, (std::vector<double>{53, 47, 32}));
  EXPECT_NEAR(r.chisq, 11.143, 5e-4);  // Hollander & Wolfe
}

TEST(Friedman, WarpbreaksMeansWithTiesCorrection) {
  const auto table =
      analysis::LongTable::read_csv(oracle_path("ref/friedman_warpbreaks_means.csv"));
  const auto x = table.numbers("x");
  // Groups: wool (A, B); blocks: tension (L, M, H); rows in the file run wool fastest.
  Eigen::MatrixXd m(3, 2);
  for (int i = 0; i < 6; ++i) m(i / 2, i % 2) = x[std::size_t(i)];
  const FriedmanResult r = friedman_test(m);
  const auto oracle = read_json(oracle_path("ref/friedman_roundingtimes.json"));
  expect_r(r.chisq, oracle["warpbreaks_means"]["statistic"], "chi2");
  expect_r(r.p, oracle["warpbreaks_means"]["p"], "p", Tolerance::kP);
}

TEST(Friedman, AllTiedBlockGivesTheCorrectedStatistic) {
  // One block with every value tied contributes nothing, as the ties correction says.
  Eigen::MatrixXd m(3, 3);
  m << 1, 2, 3, 1, 2, 3, 5, 5, 5;
  const FriedmanResult r = friedman_test(m);
  // Rank sums 4, 6, 8 -> 12*8 / (3*3*4 - 24/2) = 4.
  EXPECT_DOUBLE_EQ(r.chisq, 4.0);
}

TEST(Wilcoxon, DepressionExactTest) {
  const auto table = analysis::LongTable::read_csv(oracle_path("ref/wilcoxon_depression.csv"));
  const WilcoxonResult r = wilcoxon_signed_rank(table.numbers("first"), table.numbers("second"));
  const auto oracle = read_json(oracle_path("ref/wilcoxon_depression.json"));
  expect_r(r.v, oracle["paired_two_sided"]["statistic"], "V");
  expect_r(r.p, oracle["paired_two_sided"]["p"], "p", Tolerance::kP);
  EXPECT_TRUE(r.exact);
  EXPECT_EQ(r.n, 9);
}

TEST(Wilcoxon, TiesUseTheNormalApproximation) {
  const auto oracle = read_json(oracle_path("ref/wilcoxon_depression.json"));
  const WilcoxonResult r = wilcoxon_signed_rank({4, 3, 2}, {3, 2, 1});
  EXPECT_FALSE(r.exact);
  expect_r(r.v, oracle["ties_integer_4to2_vs_3to1"]["statistic"], "V");
  expect_r(r.p, oracle["ties_integer_4to2_vs_3to1"]["p"], "p", Tolerance::kP);
}

TEST(Wilcoxon, TiesAreJudgedOnExactDoubles) {
  // (4:2)/10 - (3:1)/10: the three differences are not bit-identical, so R sees no ties.
  const auto oracle = read_json(oracle_path("ref/wilcoxon_depression.json"));
  const WilcoxonResult r = wilcoxon_signed_rank({0.4, 0.3, 0.2}, {0.3, 0.2, 0.1});
  EXPECT_TRUE(r.exact);
  expect_r(r.p, oracle["ties_float_div10_no_ties_detected"]["p"], "p", Tolerance::kP);
}

TEST(Wilcoxon, AllDifferencesZero) {
  const WilcoxonResult r = wilcoxon_signed_rank({1, 2, 3}, {1, 2, 3});
  EXPECT_EQ(r.n, 0);
  EXPECT_EQ(r.v, 0.0);
  EXPECT_TRUE(std::isnan(r.p));
}

TEST(Psignrank, SmallTables) {
  // n = 3: sums 0..6 have counts 1,1,1,2,1,1,1 over 8 subsets.
  EXPECT_DOUBLE_EQ(psignrank(0, 3), 1.0 / 8);
  EXPECT_DOUBLE_EQ(psignrank(3, 3), 5.0 / 8);
  EXPECT_DOUBLE_EQ(psignrank(3, 3, false), 3.0 / 8);
  EXPECT_DOUBLE_EQ(psignrank(6, 3), 1.0);
}

TEST(PAdjust, HolmAndBonferroniAsR) {
  // p.adjust(c(0.01, 0.02, 0.03, 0.04, 0.05), "holm") = 0.05 0.08 0.09 0.09 0.09
  const auto holm = p_adjust_holm({0.01, 0.02, 0.03, 0.04, 0.05});
  const std::vector<double> expected = {0.05, 0.08, 0.09, 0.09, 0.09};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(holm[i], expected[i], 1e-15);
  // NaN stays NaN and is not counted.
  const auto b = p_adjust_bonferroni({0.01, NAN, 0.3});
  EXPECT_DOUBLE_EQ(b[0], 0.02);
  EXPECT_TRUE(std::isnan(b[1]));
  EXPECT_DOUBLE_EQ(b[2], 0.6);
}

TEST(Ptukey, StudentizedRangeTable) {
  // Critical values of the studentized range at alpha = .05 (Harter 1960 tables, as in every
  // statistics text): q(3, 12) = 3.773, q(4, 19) = 3.977, q(10, 60) = 4.646.
  EXPECT_NEAR(ptukey_lower(3.773, 3, 12), 0.95, 2e-4);
  EXPECT_NEAR(ptukey_lower(3.977, 4, 19), 0.95, 2e-4);
  EXPECT_NEAR(ptukey_lower(4.646, 10, 60), 0.95, 2e-4);
  EXPECT_EQ(ptukey_lower(0.0, 3, 12), 0.0);
  EXPECT_TRUE(std::isnan(ptukey_lower(1.0, 1, 12)));
  // Two means: the range of two normals is |Z1 - Z2|, so P(Q < q) = P(|T| < q / sqrt 2).
  EXPECT_NEAR(ptukey_upper(2.0 * std::sqrt(2.0), 2, 30), 0.0545, 1e-3);
}

}  // namespace
}  // namespace handlab::stats

namespace handlab::stats {
namespace {

TEST(TukeyFamily, AgreesWithTheDirectQuadrature) {
  for (const auto& [means, df] : std::vector<std::pair<double, double>>{
           {3, 5}, {4, 19}, {5, 76}, {12, 14}, {20, 19}, {20, 9999}, {6, 30000}}) {
    const TukeyFamily family(means, df);
    double worst = 0.0;
    for (double q = 0.02; q < 25.0; q *= 1.07)
      worst = std::max(worst, std::abs(family.upper(q) - ptukey_upper(q, means, df)));
    EXPECT_LT(worst, 1e-12) << means << " means, df " << df;
  }
}

}  // namespace
}  // namespace handlab::stats
