#include "studies/analysis/study_tests.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace handlab::studies {
namespace {

// A cell's levels as indices into the protocol's levels, in the protocol's order of factors.
std::vector<int> level_indices(const Protocol& protocol,
                               const std::vector<std::pair<std::string, std::string>>& cell) {
  std::vector<int> indices;
  for (const Factor& f : protocol.factors)
    for (const auto& [factor, level] : cell) {
      if (factor != f.name) continue;
      const auto at = std::find_if(f.levels.begin(), f.levels.end(),
                                   [&](const Level& l) { return l.name == level; });
      if (at == f.levels.end())
        throw std::runtime_error("the analysis names a level '" + level + "' of " + factor +
                                 " that the protocol lacks");
      indices.push_back(int(at - f.levels.begin()));
    }
  return indices;
}

std::string cell_label(const std::vector<std::pair<std::string, std::string>>& cell) {
  std::string label;
  for (const auto& [factor, level] : cell) label += (label.empty() ? "" : " ") + level;
  return label;
}

// Two cells in the protocol's order of levels (the first factor's first), labelled so.
struct Pair {
  std::string label;  // "naive fine - ours fine"
  bool swapped = false;
  std::vector<int> key;  // the first cell's level indices, then the second's
};

Pair in_order(const Protocol& protocol,
              const std::vector<std::pair<std::string, std::string>>& first,
              const std::vector<std::pair<std::string, std::string>>& second) {
  std::vector<int> a = level_indices(protocol, first), b = level_indices(protocol, second);
  Pair pair;
  pair.swapped = b < a;
  pair.label = pair.swapped ? cell_label(second) + " - " + cell_label(first)
                            : cell_label(first) + " - " + cell_label(second);
  if (pair.swapped) std::swap(a, b);
  pair.key = a;
  pair.key.insert(pair.key.end(), b.begin(), b.end());
  return pair;
}

// Tests of pairs of cells, listed in the order of their cells whatever the data's order was.
struct Ordered {
  std::vector<int> key;
  StudyTest test;
};

void append_sorted(std::vector<Ordered>& pairs, std::vector<StudyTest>& tests) {
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Ordered& x, const Ordered& y) { return x.key < y.key; });
  for (Ordered& p : pairs) tests.push_back(std::move(p.test));
}

std::vector<std::pair<std::string, std::string>> named(const std::vector<std::string>& factors,
                                                       const std::vector<std::string>& levels) {
  std::vector<std::pair<std::string, std::string>> cell;
  for (std::size_t f = 0; f < factors.size() && f < levels.size(); ++f)
    cell.emplace_back(factors[f], levels[f]);
  return cell;
}

bool on_first_repetition(const std::vector<std::pair<std::string, std::string>>& cell) {
  return std::any_of(cell.begin(), cell.end(),
                     [](const auto& c) { return c.first == "repetition" && c.second == "1"; });
}

// Whether an effect ("hand_length:manipulation") has the term `variable` among its factors.
bool involves(const std::string& effect, const std::string& variable) {
  std::size_t from = 0;
  while (from <= effect.size()) {
    const std::size_t to = std::min(effect.find(':', from), effect.size());
    if (effect.compare(from, to - from, variable) == 0 && to - from == variable.size()) return true;
    from = to + 1;
  }
  return false;
}

// A Tukey-adjusted contrast of two cells, its t signed in the pair's order.
StudyTest tukey_test(std::string name, const Pair& pair, const stats::PairwiseContrast& c,
                     const std::string& group, int participants) {
  return {std::move(name), "t",         pair.swapped ? -c.t : c.t, {c.df}, c.p_tukey, true,
          group,           participants};
}

// The effects of a completion-time ANOVA, its pairs of the protocol's cells and each factor's
// levels on the first trial, each name followed by `suffix`.
void time_tests(const analysis::AnalysisReport& t, const Protocol& protocol,
                power::SphericityCorrection correction, double alpha, const std::string& suffix,
                const std::string& group, std::vector<StudyTest>& tests) {
  std::string planned;
  for (const Factor& f : protocol.factors) planned += (planned.empty() ? "" : ":") + f.name;
  for (const stats::AnovaEffect& e : t.anova.effects) {
    const power::JudgedP j = power::judged(e, correction, alpha);
    tests.push_back({e.effect + suffix,
                     "F",
                     e.f,
                     {j.df_scale * e.df_num, j.df_scale * e.df_den},
                     j.p,
                     false,
                     group});
  }
  std::vector<Ordered> pairs;
  for (const stats::PosthocResult& r : t.posthoc)
    for (const stats::PairwiseContrast& c : r.contrasts) {
      if (c.effect != planned || !c.by.empty()) continue;
      const Pair pair = in_order(protocol, c.first, c.second);
      stats::PairwiseContrast oriented = c;
      oriented.contrast = pair.label;
      pairs.push_back({pair.key, tukey_test(power::contrast_name(oriented) + suffix, pair, c, group,
                                            t.n_subjects)});
    }
  append_sorted(pairs, tests);
  // Each factor's levels on their first trial ("strategy:repetition: naive 1 - ours 1"): how
  // they compare before any practice, Tukey over the factor-by-repetition cells.
  std::vector<Ordered> first_trials;
  for (const stats::PosthocResult& r : t.posthoc)
    for (const stats::PairwiseContrast& c : r.contrasts) {
      if (!c.by.empty() || c.first.size() != 2 || !on_first_repetition(c.first) ||
          !on_first_repetition(c.second))
        continue;
      const Pair pair = in_order(protocol, c.first, c.second);
      first_trials.push_back({pair.key, tukey_test(c.effect + ": " + pair.label + suffix, pair, c,
                                                   group, t.n_subjects)});
    }
  append_sorted(first_trials, tests);
}

// Friedman's test of one item of a nonparametric analysis and its pairwise Wilcoxon tests.
void item_tests(const analysis::AnalysisReport& r, const std::string& item,
                const StudyDatabaseAnalysis& a, const std::string& group,
                std::vector<StudyTest>& tests) {
  for (const analysis::FriedmanItem& f : r.friedman)
    if (f.dv == item)
      tests.push_back(
          {f.dv + " (Friedman)", "chi2", f.result.chisq, {f.result.df}, f.result.p, false, group});
  std::vector<Ordered> pairs;
  for (const analysis::WilcoxonPair& w : r.wilcoxon) {
    if (w.dv != item) continue;
    const Pair pair =
        in_order(a.protocol, named(a.study.factors, w.first), named(a.study.factors, w.second));
    // V sums the ranks of the positive differences: the other way round, of the negative.
    const double all_ranks = 0.5 * w.result.n * (w.result.n + 1.0);
    pairs.push_back({pair.key,
                     {w.dv + ": " + pair.label + " (Wilcoxon)",
                      "V",
                      pair.swapped ? all_ranks - w.result.v : w.result.v,
                      {},
                      w.p_bonferroni,
                      true,
                      group}});
  }
  append_sorted(pairs, tests);
}

}  // namespace

StudyTests study_tests(const StudyDatabaseAnalysis& a, power::SphericityCorrection correction,
                       double alpha) {
  StudyTests out;
  const Protocol& protocol = a.protocol;
  if (!a.completion_time) {
    out.warning = "completion time not analysed: " + a.completion_time_not_computed;
  } else {
    const analysis::AnalysisReport& t = *a.completion_time;
    time_tests(t, protocol, correction, alpha, "", kTestsTimeoutsAtLimit, out.tests);
    // The follow-up ANOVAs with one participant variable each (a covariate or a between
    // factor): the effects that involve the variable, "hand_length:manipulation (covariate)".
    for (const ParticipantVariableAnalysis& v : a.participant_variables) {
      if (!v.result) continue;
      const std::string kind = v.between ? " (between)" : " (covariate)";
      for (const stats::AnovaEffect& e : v.result->anova.effects) {
        if (!involves(e.effect, v.variable)) continue;
        const power::JudgedP j = power::judged(e, correction, alpha);
        out.tests.push_back({e.effect + kind,
                             "F",
                             e.f,
                             {j.df_scale * e.df_num, j.df_scale * e.df_den},
                             j.p,
                             false,
                             kTestsTimeoutsAtLimit});
      }
    }
    if (!t.dropped_subjects.empty())
      out.warning = std::to_string(t.dropped_subjects.size()) +
                    " participant(s) left out, lacking a result in some cell";
  }
  if (a.time_without_timeouts.result)
    time_tests(*a.time_without_timeouts.result, protocol, correction, alpha, " (timeouts left out)",
               kTestsTimeoutsLeftOut, out.tests);
  if (a.success.result) item_tests(*a.success.result, "success_rate", a, kTestsSuccess, out.tests);
  if (a.questionnaire) {
    for (const QuestionnaireItem& item : protocol.items)
      item_tests(*a.questionnaire, item.id, a, kTestsQuestionnaire, out.tests);
  } else if (out.warning.empty() && !protocol.items.empty()) {
    out.warning = "questionnaire not analysed: " + a.questionnaire_not_computed;
  }
  return out;
}

}  // namespace handlab::studies
