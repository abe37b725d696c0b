// Morris's elementary effects: the design's trajectories step every parameter once by the
// grid's delta, and the indices are exact where the answer is known: a linear function's
// effects are its coefficients with no spread, a product's spread shows the interaction, and a
// parameter the output ignores has none.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "studies/protocol/protocol.h"
#include "studies/sensitivity/model_sensitivity.h"
#include "studies/sensitivity/morris.h"

namespace handlab::studies {
namespace {

TEST(MorrisDesign, EachTrajectoryStepsEveryParameterOnceOnTheGrid) {
  const int k = 5, r = 7, p = 4;
  const MorrisDesign d = morris_design(k, r, p, 3);
  ASSERT_EQ(d.points.size(), std::size_t(r * (k + 1)));
  const double delta = 4.0 / 6.0;
  for (int t = 0; t < r; ++t) {
    std::set<int> stepped;
    EXPECT_EQ(d.steps[std::size_t(t * (k + 1))].parameter, -1);
    for (int j = 1; j <= k; ++j) {
      const std::size_t at = std::size_t(t * (k + 1) + j);
      const MorrisStep& s = d.steps[at];
      ASSERT_GE(s.parameter, 0);
      EXPECT_TRUE(stepped.insert(s.parameter).second) << "parameter stepped twice";
      EXPECT_NEAR(std::abs(s.delta), delta, 1e-12);
      for (int i = 0; i < k; ++i) {
        const double before = d.points[at - 1][std::size_t(i)],
                     after = d.points[at][std::size_t(i)];
        EXPECT_NEAR(after - before, i == s.parameter ? s.delta : 0.0, 1e-12);
        EXPECT_NEAR(after * (p - 1), std::round(after * (p - 1)), 1e-9) << "on the grid";
        EXPECT_GE(after, 0.0);
        EXPECT_LE(after, 1.0);
      }
    }
    EXPECT_EQ(int(stepped.size()), k);
  }
  // Both directions occur, and the same seed gives the same design.
  int up = 0, down = 0;
  for (const MorrisStep& s : d.steps)
    (s.delta > 0 ? up : s.delta < 0 ? down : up) += s.parameter >= 0;
  EXPECT_GT(up, 0);
  EXPECT_GT(down, 0);
  EXPECT_EQ(morris_design(k, r, p, 3).points, d.points);
  EXPECT_NE(morris_design(k, r, p, 4).points, d.points);
  EXPECT_THROW(morris_design(k, r, 3, 1), std::invalid_argument);
}

TEST(MorrisIndices, ExactForLinearFunctionsAndInteractions) {
  const MorrisDesign d = morris_design(4, 10, 4, 11);
  std::vector<double> linear, product;
  for (const std::vector<double>& x : d.points) {
    linear.push_back(3.0 * x[0] - 2.0 * x[1] + 0.5 * x[3]);
    product.push_back(x[0] * x[1]);
  }
  const std::vector<MorrisIndex> l = morris_indices(d, linear);
  const double coefficients[] = {3.0, -2.0, 0.0, 0.5};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(l[std::size_t(i)].mu, coefficients[i], 1e-12);
    EXPECT_NEAR(l[std::size_t(i)].mu_star, std::abs(coefficients[i]), 1e-12);
    EXPECT_NEAR(l[std::size_t(i)].sigma, 0.0, 1e-12);
    EXPECT_EQ(l[std::size_t(i)].effects, 10);
  }
  const std::vector<MorrisIndex> m = morris_indices(d, product);
  EXPECT_GT(m[0].sigma, 0.05);  // x0's effect is x1: it varies with the other parameter
  EXPECT_GT(m[1].sigma, 0.05);
  EXPECT_EQ(m[2].mu_star, 0.0);
  // A failed point (NaN) leaves out the two effects it takes part in, no more.
  product[6] = std::nan("");  // inside a trajectory (of five points)
  const std::vector<MorrisIndex> gap = morris_indices(d, product);
  int effects = 0;
  for (const MorrisIndex& g : gap) effects += g.effects;
  EXPECT_EQ(effects, 4 * 10 - 2);
}

// The sensitivity's default tests follow the protocol's factors and labels: the study's
// three, and a 3 x 3 design's with its own labels.
TEST(ModelSensitivity, DefaultTestsNameTheProtocolsFactorsAndLabels) {
  const std::string source = HANDLAB_SOURCE_DIR;
  EXPECT_EQ(
      default_sensitivity_outputs(read_protocol(source + "/studies/fine-manipulation-2021.json")),
      (std::vector<std::string>{"strategy:manipulation", "repetition",
                                "strategy:manipulation: naive fine - ours fine"}));
  std::string text = read_protocol(source + "/studies/examples/three-by-three.json").text;
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"naive\", \"method\"", "\"A\", \"method\""},
        {"\"ours\", \"method\"", "\"B\", \"method\""},
        {"\"name\": \"fine\"", "\"name\": \"1 cm\""}})
    text.replace(text.find(from), from.size(), to);
  EXPECT_EQ(default_sensitivity_outputs(parse_protocol(text, "relabelled.json")),
            (std::vector<std::string>{"strategy:manipulation", "repetition",
                                      "strategy:manipulation: A 1 cm - B 1 cm"}));
  // One factor: no contrast; three: the first factor's levels at the others' last.
  const std::string study = read_protocol(source + "/studies/fine-manipulation-2021.json").text;
  const std::size_t from = study.find(",\n    {\"name\": \"manipulation\"");
  const std::size_t to = study.find("\n  ],\n  \"blocks\"");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(default_sensitivity_outputs(
                parse_protocol(study.substr(0, from) + study.substr(to), "one.json")),
            (std::vector<std::string>{"strategy", "repetition"}));
  const std::string three = study.substr(0, to) +
                            ",\n    {\"name\": \"hand_length\", \"levels\": [{\"name\": \"small\", "
                            "\"length\": 0.18}, {\"name\": \"large\", \"length\": 0.23}]}" +
                            study.substr(to);
  EXPECT_EQ(default_sensitivity_outputs(parse_protocol(three, "three.json")).back(),
            "strategy:manipulation:hand_length: naive fine large - ours fine large");
}

}  // namespace
}  // namespace handlab::studies
