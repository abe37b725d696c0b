// Simulation-based power against exact answers: a paired t test's power from the noncentral
// t and a one-way RM-ANOVA's under sphericity from the noncentral F (Boost.Math), each within
// three Monte Carlo standard errors; the estimated model recovering a large pilot's
// parameters; determinism over thread counts; the model file's checks.
#include <cmath>

#include <gtest/gtest.h>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "analysis/power/power_analysis.h"
#include "analysis/power/power_model.h"

namespace handlab::power {
namespace {

namespace bm = boost::math;

PowerDesign one_factor(int levels) {
  PowerDesign d;
  stats::Factor f{"condition", {}};
  for (int k = 0; k < levels; ++k) f.levels.push_back("c" + std::to_string(k + 1));
  d.factors.push_back(f);
  return d;
}

PowerModel exchangeable_model(const PowerDesign& d, const Eigen::VectorXd& mean, double sd,
                              double r) {
  PowerModel m;
  m.design = d;
  m.mean = mean;
  m.sd = Eigen::VectorXd::Constant(d.cells(), sd);
  m.correlation = Eigen::MatrixXd::Constant(d.cells(), d.cells(), r);
  m.correlation.diagonal().setOnes();
  m.contrast_effects = {"condition"};
  return m;
}

const PowerEstimate& find(const std::vector<PowerEstimate>& list, const std::string& name) {
  for (const PowerEstimate& e : list)
    if (e.name == name) return e;
  throw std::runtime_error("no estimate named " + name);
}

// 4,000 simulations: the Monte Carlo SE of a power near 0.5 is 0.008, so the bound of three
// SEs is about 0.024 (10,000 simulations in docs/power.md).
constexpr int kSims = 4000;

// The paired t test's power: the noncentral t beyond the two-sided critical value.
double paired_t_power(double n, double delta, double sd, double r) {
  const double df = n - 1;
  const double ncp = delta / (sd * std::sqrt(2 * (1 - r))) * std::sqrt(n);
  const double critical = bm::quantile(bm::complement(bm::students_t(df), 0.025));
  const bm::non_central_t t(df, ncp);
  return bm::cdf(bm::complement(t, critical)) + bm::cdf(t, -critical);
}

TEST(PowerSimulation, PairedTTestMatchesTheNoncentralT) {
  const PowerDesign d = one_factor(2);
  const double delta = 0.5, sd = 1.0, r = 0.5;
  const PowerModel m = exchangeable_model(d, Eigen::Vector2d(0.0, delta), sd, r);
  PowerOptions o;
  o.n = {12, 24};
  o.sims = kSims;
  o.seed = 7;
  o.threads = 2;
  const PowerReport report = simulate_power(m, o);
  const PowerEstimate& effect = find(report.effects, "condition");
  const PowerEstimate& contrast = find(report.contrasts, "condition: c1 - c2");
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    const double n = o.n[k];
    const double exact = paired_t_power(n, delta, sd, r);
    const double se = std::sqrt(exact * (1 - exact) / kSims);
    EXPECT_NEAR(effect.power[k], exact, 3 * se) << "N = " << n;
    // With two means the Tukey test is the t test.
    EXPECT_EQ(contrast.power[k], effect.power[k]) << "N = " << n;
    EXPECT_NEAR(effect.mc_se[k], se, 0.1 * se);
    EXPECT_LT(effect.lower[k], effect.power[k]);
    EXPECT_GT(effect.upper[k], effect.power[k]);
  }
  // The exact path gives the same answer from the model's moments.
  const PowerReport exact = exact_power(m, o);
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    const double expected = paired_t_power(o.n[k], delta, sd, r);
    EXPECT_NEAR(find(exact.contrasts, "condition: c1 - c2").power[k], expected, 1e-9);
    EXPECT_NEAR(find(exact.effects, "condition").power[k], expected, 1e-6);  // F = t^2
  }
}

TEST(PowerSimulation, OneWayRmAnovaUnderSphericityMatchesTheNoncentralF) {
  const PowerDesign d = one_factor(4);
  const double sd = 2.0, r = 0.6;
  const Eigen::Vector4d mean(10.0, 10.4, 10.9, 10.2);
  const PowerModel m = exchangeable_model(d, mean, sd, r);
  PowerOptions o;
  o.n = {10, 16};
  o.sims = kSims;
  o.seed = 11;
  o.threads = 2;
  o.correction = SphericityCorrection::kNone;  // compound symmetry: the uncorrected F is exact
  const PowerReport report = simulate_power(m, o);
  const PowerReport exact = exact_power(m, o);
  const double spread = (mean.array() - mean.mean()).square().sum();
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    const double n = o.n[k], df1 = 3, df2 = 3 * (n - 1);
    const double lambda = n * spread / (sd * sd * (1 - r));
    const double critical = bm::quantile(bm::complement(bm::fisher_f(df1, df2), 0.05));
    const double expected = bm::cdf(bm::complement(bm::non_central_f(df1, df2, lambda), critical));
    const double se = std::sqrt(expected * (1 - expected) / kSims);
    EXPECT_NEAR(find(report.effects, "condition").power[k], expected, 3 * se) << "N = " << n;
    EXPECT_NEAR(find(exact.effects, "condition").power[k], expected, 1e-9) << "N = " << n;
  }
}

TEST(PowerSimulation, TheSameForASeedWhateverTheThreads) {
  PowerDesign d;
  d.factors = {{"strategy", {"naive", "ours"}}, {"manipulation", {"gross", "fine"}}};
  d.repetitions = 3;
  Eigen::VectorXd mean(12);
  for (int c = 0; c < 12; ++c) mean[c] = 8 + 0.3 * (c % 4) - 0.2 * (c / 4);
  PowerModel m = exchangeable_model(d, mean, 2.0, 0.5);
  m.contrast_effects = {"strategy:manipulation"};
  m.missing = 0.01;
  PowerItem item;
  item.name = "precision";
  item.mean = Eigen::Vector4d(4.0, 3.6, 3.8, 2.9);
  item.sd = 0.8;
  item.correlation = 0.3;
  m.items.push_back(item);
  PowerOptions o;
  o.n = {8, 12};
  o.sims = 60;
  o.seed = 3;
  o.threads = 1;
  const PowerReport one = simulate_power(m, o);
  o.threads = 2;
  const PowerReport two = simulate_power(m, o);
  ASSERT_EQ(one.effects.size(), two.effects.size());
  for (std::size_t e = 0; e < one.effects.size(); ++e)
    EXPECT_EQ(one.effects[e].power, two.effects[e].power) << one.effects[e].name;
  for (std::size_t c = 0; c < one.contrasts.size(); ++c)
    EXPECT_EQ(one.contrasts[c].power, two.contrasts[c].power) << one.contrasts[c].name;
  EXPECT_EQ(one.warnings, two.warnings);
  // Effects as analyze names them, the items' tests after them.
  EXPECT_NO_THROW(find(one.effects, "strategy:manipulation"));
  EXPECT_NO_THROW(find(one.effects, "strategy:manipulation:repetition"));
  EXPECT_NO_THROW(find(one.effects, "precision (Friedman)"));
  EXPECT_NO_THROW(find(one.contrasts, "strategy:manipulation: naive fine - ours fine"));
  EXPECT_NO_THROW(find(one.contrasts, "precision: naive fine - ours fine (Wilcoxon)"));
  // 1 % missing trials over 12 cells leave someone out in most studies: warned.
  EXPECT_GT(one.warnings[0], 10);
  o.seed = 4;
  EXPECT_NE(simulate_power(m, o).effects[0].power, one.effects[0].power);
}

TEST(PowerModelEstimate, RecoversTheParametersOfALargeSimulatedPilot) {
  PowerDesign d;
  d.factors = {{"strategy", {"naive", "ours"}}, {"manipulation", {"gross", "fine"}}};
  d.repetitions = 2;
  const int cells = d.cells();
  PowerModel truth;
  truth.design = d;
  truth.mean.resize(cells);
  truth.sd.resize(cells);
  for (int c = 0; c < cells; ++c) {
    truth.mean[c] = 6 + 0.5 * c;
    truth.sd[c] = 1 + 0.25 * (c % 3);
  }
  // A correlation that is not exchangeable: decaying with the cells' distance.
  truth.correlation.resize(cells, cells);
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) truth.correlation(i, j) = std::pow(0.7, std::abs(i - j));
  util::PortableRandom random(99);
  const int n = 4000;
  const SimulatedData pilot = simulate_data(truth, n, random);
  const PowerModel estimated = estimate_power_model(d, pilot.cells);
  for (int c = 0; c < cells; ++c) {
    EXPECT_NEAR(estimated.mean[c], truth.mean[c], 4 * truth.sd[c] / std::sqrt(n)) << c;
    EXPECT_NEAR(estimated.sd[c], truth.sd[c], 0.05 * truth.sd[c]) << c;
  }
  EXPECT_LT((estimated.correlation - truth.correlation).cwiseAbs().maxCoeff(), 0.05);
  // A small pilot (fewer participants than cells) gets one correlation, and says so.
  const PowerModel small = estimate_power_model(d, pilot.cells.topRows(6));
  EXPECT_DOUBLE_EQ(small.correlation(0, 1), small.correlation(2, 5));
  bool said = false;
  for (const std::string& note : small.notes)
    said = said || note.find("one value") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(PowerModelFile, ReadsConditionsByLabelAndRefusesWhatIsWrong) {
  PowerDesign d;
  d.factors = {{"strategy", {"naive", "ours"}}, {"manipulation", {"gross", "fine"}}};
  d.repetitions = 2;
  const std::string ok = R"({"format": "handlab-power-model", "version": 1,
    "means": {"naive-gross": 8, "ours-gross": 8, "naive-fine": 12, "ours-fine": 10},
    "repetition_effect": [1, -1], "sd": 3, "correlation": 0.5,
    "covariates": [{"name": "hand_length", "mean": 0.188, "sd": 0.012, "slope": {"naive-fine": 50}}]})";
  const PowerModel m = parse_power_model(ok, d);
  ASSERT_EQ(m.mean.size(), 8);
  EXPECT_DOUBLE_EQ(m.mean[0], 9.0);  // naive-gross, repetition 1
  EXPECT_DOUBLE_EQ(m.mean[7], 9.0);  // ours-fine, repetition 2
  EXPECT_DOUBLE_EQ(m.covariates[0].slope[2], 50.0);
  EXPECT_DOUBLE_EQ(m.covariates[0].slope[6], 50.0);
  EXPECT_DOUBLE_EQ(m.covariates[0].slope[0], 0.0);
  EXPECT_EQ(m.contrast_effects, std::vector<std::string>{"strategy:manipulation"});
  auto message = [&](const std::string& text) {
    try {
      parse_power_model(text, d, "m.json");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(
      message(
          R"({"means": {"naive-gross": 8, "ours-gross": 8, "naive-fine": 12, "ours-small": 1}, "sd": 1})")
          .find("'ours-small', which is not a condition"),
      std::string::npos);
  EXPECT_NE(message(R"({"means": {"naive-gross": 8, "ours-gross": 8, "naive-fine": 12}, "sd": 1})")
                .find("lacks condition 'ours-fine'"),
            std::string::npos);
  EXPECT_NE(message(R"({"means": 1, "sd": 1, "correlation": 1.5})").find("'correlation'"),
            std::string::npos);
  EXPECT_NE(message(R"({"means": 1, "sd": 1, "repetition_effect": [1, 2, 3]})").find("2 numbers"),
            std::string::npos);
}

}  // namespace
}  // namespace handlab::power
