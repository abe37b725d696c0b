#include "analysis/stats/rm_data.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace handlab::stats {
namespace {

using analysis::DataError;

std::string where(const analysis::LongTable& t, std::size_t row) {
  return t.source() + " line " + std::to_string(t.line(row));
}

Factor as_factor(const std::string& name, const analysis::LongTable::Codes& codes,
                 const analysis::LongTable& table) {
  if (codes.levels.size() < 2)
    throw DataError(table.source() + ", column '" + name +
                    "': a factor needs at least two levels, found only '" + codes.levels.front() +
                    "'");
  return {name, codes.levels};
}

}  // namespace

std::vector<int> RmData::cell_levels(int c) const {
  std::vector<int> levels(within.size());
  for (std::size_t f = 0; f < within.size(); ++f) {
    const int k = int(within[f].levels.size());
    levels[f] = c % k;
    c /= k;
  }
  return levels;
}

std::string RmData::effect_label(const std::vector<int>& within_factors) const {
  std::string label;
  for (int f : within_factors) label += (label.empty() ? "" : ":") + within[std::size_t(f)].name;
  return label;
}

RmData prepare_rm_data(const analysis::LongTable& table, const RmDesignSpec& spec) {
  if (spec.within.empty())
    throw DataError("a repeated-measures analysis needs at least one within factor");
  std::set<std::string> seen;
  for (const auto& list : {spec.within, spec.between, spec.covariates,
                           std::vector<std::string>{spec.subject, spec.dv}})
    for (const auto& name : list)
      if (!seen.insert(name).second)
        throw DataError("column '" + name + "' is named twice in the design");
  for (const auto& name : spec.observed)
    if (std::find(spec.between.begin(), spec.between.end(), name) == spec.between.end() &&
        std::find(spec.covariates.begin(), spec.covariates.end(), name) == spec.covariates.end())
      throw DataError("observed variable '" + name + "' must be a between factor or a covariate");

  RmData data;
  data.covariates = spec.covariates;
  data.observed = spec.observed;
  const auto subjects = table.factor_codes(spec.subject);
  std::vector<analysis::LongTable::Codes> within_codes, between_codes;
  for (const auto& name : spec.within) {
    within_codes.push_back(table.factor_codes(name));
    data.within.push_back(as_factor(name, within_codes.back(), table));
  }
  for (const auto& name : spec.between) {
    between_codes.push_back(table.factor_codes(name));
    data.between.push_back(as_factor(name, between_codes.back(), table));
  }
  const std::vector<double> dv = table.numbers(spec.dv);
  std::vector<std::vector<double>> covariate_columns;
  for (const auto& name : spec.covariates) covariate_columns.push_back(table.numbers(name));

  int cells = 1;
  for (const auto& f : data.within) cells *= int(f.levels.size());
  const std::size_t n_all = subjects.levels.size();
  std::vector<double> sum(n_all * std::size_t(cells), 0.0);
  std::vector<int> count(n_all * std::size_t(cells), 0);
  std::vector<std::size_t> first_row(n_all, table.rows());

  for (std::size_t r = 0; r < table.rows(); ++r) {
    const auto s = std::size_t(subjects.codes[r]);
    if (first_row[s] == table.rows()) {
      first_row[s] = r;
    } else {
      const std::size_t f = first_row[s];
      for (std::size_t b = 0; b < between_codes.size(); ++b)
        if (between_codes[b].codes[r] != between_codes[b].codes[f])
          throw DataError(where(table, r) + ", column '" + spec.between[b] + "': participant " +
                          subjects.levels[s] + " has more than one value of a between factor");
      for (std::size_t k = 0; k < covariate_columns.size(); ++k)
        if (covariate_columns[k][r] != covariate_columns[k][f])
          throw DataError(where(table, r) + ", column '" + spec.covariates[k] + "': participant " +
                          subjects.levels[s] + " has more than one value of a covariate");
    }
    int cell = 0, stride = 1;
    for (std::size_t f = 0; f < within_codes.size(); ++f) {
      cell += stride * within_codes[f].codes[r];
      stride *= int(data.within[f].levels.size());
    }
    sum[s * std::size_t(cells) + std::size_t(cell)] += dv[r];
    count[s * std::size_t(cells) + std::size_t(cell)] += 1;
  }

  bool averaged = false;
  std::vector<std::size_t> kept;
  for (std::size_t s = 0; s < n_all; ++s) {
    const int* c = count.data() + s * std::size_t(cells);
    if (std::any_of(c, c + cells, [](int n) { return n == 0; })) {
      data.dropped_subjects.push_back(subjects.levels[s]);
      continue;
    }
    averaged |= std::any_of(c, c + cells, [](int n) { return n > 1; });
    kept.push_back(s);
  }
  if (!data.dropped_subjects.empty()) {
    std::string ids;
    for (const auto& id : data.dropped_subjects) ids += (ids.empty() ? "" : ", ") + id;
    data.warnings.push_back("Missing values for following ID(s): " + ids +
                            ". Removing those cases from the analysis.");
  }
  if (averaged)
    data.warnings.push_back(
        "More than one observation per participant and cell: the mean is used.");
  if (kept.size() < 2)
    throw DataError(table.source() + ": fewer than two participants have every within cell");

  const auto n = Eigen::Index(kept.size());
  data.y.resize(n, cells);
  data.covariate_values.resize(n, Eigen::Index(spec.covariates.size()));
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::size_t s = kept[std::size_t(i)];
    const std::size_t f = first_row[s];
    data.subjects.push_back(subjects.levels[s]);
    std::vector<int> between_levels;
    for (const auto& codes : between_codes) between_levels.push_back(codes.codes[f]);
    data.between_levels.push_back(std::move(between_levels));
    for (int c = 0; c < cells; ++c)
      data.y(i, c) = sum[s * std::size_t(cells) + std::size_t(c)] /
                     count[s * std::size_t(cells) + std::size_t(c)];
    for (std::size_t k = 0; k < covariate_columns.size(); ++k)
      data.covariate_values(i, Eigen::Index(k)) = covariate_columns[k][f];
  }
  // Covariates are centred on the mean over the participants analysed, as afex expects.
  for (Eigen::Index k = 0; k < data.covariate_values.cols(); ++k) {
    const double mean = data.covariate_values.col(k).mean();
    data.covariate_means.push_back(mean);
    data.covariate_values.col(k).array() -= mean;
  }
  // A between level nobody analysed has would make the design singular.
  for (std::size_t b = 0; b < data.between.size(); ++b) {
    std::vector<bool> present(data.between[b].levels.size(), false);
    for (const auto& levels : data.between_levels) present[std::size_t(levels[b])] = true;
    for (std::size_t l = 0; l < present.size(); ++l)
      if (!present[l])
        throw DataError("between factor '" + data.between[b].name +
                        "': no complete participant has level '" + data.between[b].levels[l] + "'");
  }
  return data;
}

}  // namespace handlab::stats
