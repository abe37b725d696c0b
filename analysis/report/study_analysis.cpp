#include "analysis/report/study_analysis.h"

#include <cmath>
#include <map>
#include <numeric>

#include "analysis/stats/design_matrices.h"
#include "analysis/stats/p_adjust.h"

namespace handlab::analysis {
namespace {

// Per-cell descriptives over participants' cell values (their mean when a cell has several
// rows), counting every participant who has the cell, complete or not.
std::vector<CellDescriptives> cell_descriptives(const LongTable& table,
                                                const stats::RmDesignSpec& spec,
                                                const stats::RmData& data) {
  std::vector<std::string> factors = spec.within;
  std::vector<const stats::Factor*> levels;
  for (const auto& f : data.within) levels.push_back(&f);
  for (const auto& f : data.between) {
    factors.push_back(f.name);
    levels.push_back(&f);
  }
  std::vector<LongTable::Codes> codes;
  for (const auto& f : factors) codes.push_back(table.factor_codes(f));
  const LongTable::Codes subjects = table.factor_codes(spec.subject);
  const std::vector<double> dv = table.numbers(spec.dv);

  std::size_t cells = 1;
  for (const auto* f : levels) cells *= f->levels.size();
  const std::size_t n = subjects.levels.size();
  std::vector<double> sum(cells * n, 0.0);
  std::vector<int> count(cells * n, 0);
  for (std::size_t r = 0; r < table.rows(); ++r) {
    std::size_t cell = 0, stride = 1;
    for (std::size_t k = 0; k < codes.size(); ++k) {
      cell += stride * std::size_t(codes[k].codes[r]);
      stride *= levels[k]->levels.size();
    }
    sum[cell * n + std::size_t(subjects.codes[r])] += dv[r];
    count[cell * n + std::size_t(subjects.codes[r])] += 1;
  }
  std::vector<CellDescriptives> out;
  std::vector<double> values;
  for (std::size_t cell = 0; cell < cells; ++cell) {
    values.clear();
    for (std::size_t s = 0; s < n; ++s)
      if (count[cell * n + s] > 0) values.push_back(sum[cell * n + s] / count[cell * n + s]);
    if (values.empty()) continue;
    CellDescriptives c;
    std::size_t rest = cell;
    for (std::size_t k = 0; k < factors.size(); ++k) {
      c.cell.emplace_back(factors[k], levels[k]->levels[rest % levels[k]->levels.size()]);
      rest /= levels[k]->levels.size();
    }
    c.d = stats::describe(values);
    out.push_back(std::move(c));
  }
  return out;
}

void run_nonparametric(const LongTable& table, const AnalysisRequest& request,
                       AnalysisReport* report) {
  const auto& spec = request.design;
  std::vector<stats::Factor> factors;
  for (const auto& name : spec.within) {
    // The table's order of the levels: the data's, or the design's (LongTable::order_levels).
    stats::Factor f{name, table.factor_codes(name).levels};
    if (f.levels.size() < 2)
      throw DataError(table.source() + ", column '" + name +
                      "': a factor needs at least two levels");
    factors.push_back(f);
  }
  // Conditions with the first factor outermost: "Gross Naive", "Gross Ours", "Fine Naive", ...
  int conditions = 1;
  for (const auto& f : factors) conditions *= int(f.levels.size());
  auto condition_of = [&](std::size_t row) {
    int index = 0;
    for (std::size_t k = 0; k < factors.size(); ++k) {
      const auto& ls = factors[k].levels;
      index = index * int(ls.size()) +
              int(std::find(ls.begin(), ls.end(), table.cell(row, table.column(factors[k].name))) -
                  ls.begin());
    }
    return index;
  };
  auto condition_levels = [&](int index) {
    std::vector<std::string> parts(factors.size());
    for (std::size_t k = factors.size(); k-- > 0;) {
      const int n = int(factors[k].levels.size());
      parts[k] = factors[k].levels[std::size_t(index % n)];
      index /= n;
    }
    return parts;
  };
  auto condition_label = [&](int index) {
    const std::vector<std::string> parts = condition_levels(index);
    std::string label;
    for (const auto& p : parts) label += (label.empty() ? "" : " ") + p;
    return label;
  };

  const std::size_t subject_col = table.column(spec.subject);
  std::vector<std::string> subjects;
  std::map<std::string, std::size_t> subject_index;
  for (std::size_t r = 0; r < table.rows(); ++r)
    if (subject_index.emplace(table.cell(r, subject_col), subjects.size()).second)
      subjects.push_back(table.cell(r, subject_col));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& item : request.nonparametric_items) {
    const std::vector<double> values = table.numbers(item);
    Eigen::MatrixXd m = Eigen::MatrixXd::Constant(Eigen::Index(subjects.size()), conditions, nan);
    for (std::size_t r = 0; r < table.rows(); ++r) {
      double& cell = m(Eigen::Index(subject_index[table.cell(r, subject_col)]), condition_of(r));
      if (!std::isnan(cell))
        throw DataError(table.source() + " line " + std::to_string(table.line(r)) +
                        ": participant " + table.cell(r, subject_col) +
                        " has two rows for one condition of '" + item + "'");
      cell = values[r];
    }
    // Friedman on participants with every condition.
    FriedmanItem fr;
    fr.dv = item;
    std::vector<Eigen::Index> complete;
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (m.row(i).array().isNaN().any())
        fr.dropped_subjects.push_back(subjects[std::size_t(i)]);
      else
        complete.push_back(i);
    }
    if (complete.size() < 2)
      throw DataError("'" + item + "': fewer than two participants answered every condition");
    Eigen::MatrixXd blocks(Eigen::Index(complete.size()), conditions);
    for (std::size_t i = 0; i < complete.size(); ++i)
      blocks.row(Eigen::Index(i)) = m.row(complete[i]);
    fr.result = stats::friedman_test(blocks);
    if (!fr.dropped_subjects.empty())
      report->warnings.push_back("'" + item +
                                 "': Friedman test without participants lacking a condition (" +
                                 std::to_string(fr.dropped_subjects.size()) + ")");
    report->friedman.push_back(fr);

    // Wilcoxon for every pair of conditions, on participants with both.
    std::vector<WilcoxonPair> pairs;
    std::vector<double> p;
    for (int a = 0; a < conditions; ++a) {
      for (int b = a + 1; b < conditions; ++b) {
        std::vector<double> x, y;
        for (Eigen::Index i = 0; i < m.rows(); ++i)
          if (!std::isnan(m(i, a)) && !std::isnan(m(i, b))) {
            x.push_back(m(i, a));
            y.push_back(m(i, b));
          }
        WilcoxonPair w{item,
                       condition_label(a) + " - " + condition_label(b),
                       condition_levels(a),
                       condition_levels(b),
                       stats::wilcoxon_signed_rank(x, y),
                       0,
                       0};
        p.push_back(w.result.p);
        pairs.push_back(w);
      }
    }
    const auto bonferroni = stats::p_adjust_bonferroni(p);
    const auto holm = stats::p_adjust_holm(p);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      pairs[i].p_bonferroni = bonferroni[i];
      pairs[i].p_holm = holm[i];
      report->wilcoxon.push_back(pairs[i]);
    }
  }
  report->n_subjects = int(subjects.size());
}

}  // namespace

AnalysisReport run_analysis(const LongTable& given, const AnalysisRequest& request) {
  AnalysisReport report;
  report.request = request;
  report.source = given.source();
  if (request.design.within.empty()) throw DataError("name at least one within factor (--within)");
  if (report.nonparametric()) {
    run_nonparametric(given, request, &report);
    return report;
  }
  // A missing observation (NA or an empty cell, as R reads them; a skipped trial in handlab's
  // export) is left out before a cell's observations are averaged; a participant who then
  // lacks a whole cell is dropped, as afex drops one with a missing cell.
  const LongTable table = given.without(request.design.dv, {"NA", ""});
  if (table.rows() == 0)
    throw DataError(given.source() + ": no row has a value of '" + request.design.dv +
                    "' (every one is NA or empty)");
  // Leaving rows out must not change the design: a cell with no observation left is an error,
  // a participant with none is named.
  for (const std::string& f : request.design.within)
    for (const std::string& level : given.factor_codes(f).levels) {
      const std::vector<std::string> kept = table.factor_codes(f).levels;
      if (std::find(kept.begin(), kept.end(), level) == kept.end())
        throw DataError(given.source() + ": no row of " + f + " '" + level + "' has a value of '" +
                        request.design.dv + "' (every one is NA or empty)");
    }
  std::string without_any;
  {
    const std::vector<std::string> kept = table.factor_codes(request.design.subject).levels;
    for (const std::string& who : given.factor_codes(request.design.subject).levels)
      if (std::find(kept.begin(), kept.end(), who) == kept.end())
        without_any += (without_any.empty() ? "" : ", ") + who;
  }
  const stats::RmData data = stats::prepare_rm_data(table, request.design);
  report.n_subjects = int(data.subjects.size());
  report.dropped_subjects = data.dropped_subjects;
  if (table.rows() < given.rows())
    report.warnings.push_back(std::to_string(given.rows() - table.rows()) +
                              (given.rows() - table.rows() == 1 ? " row" : " rows") + " with no " +
                              request.design.dv + " (NA) left out before the cells were averaged");
  if (!without_any.empty())
    report.warnings.push_back("no " + request.design.dv +
                              " at all (every row NA), left out: " + without_any);
  report.warnings.insert(report.warnings.end(), data.warnings.begin(), data.warnings.end());
  report.covariate_means = data.covariate_means;
  report.anova = stats::rm_anova(data);
  std::vector<std::string> effects = request.posthoc;
  if (effects.empty()) {
    for (const auto& e : stats::within_effects(int(data.within.size())))
      if (!e.empty()) effects.push_back(data.effect_label(e));
  }
  for (const auto& e : effects) {
    stats::PosthocSpec spec = stats::PosthocSpec::parse(e, data);
    spec.r_level_names = request.r_level_names;
    report.posthoc.push_back(stats::pairwise_comparisons(data, spec));
  }
  report.descriptives = cell_descriptives(table, request.design, data);
  return report;
}

}  // namespace handlab::analysis
