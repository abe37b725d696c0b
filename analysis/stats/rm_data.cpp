#include "analysis/stats/rm_data.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace handlab::stats {
namespace {

using analysis::DataError;

std::string where(const analysis::LongTable& t, std::size_t row) {
  return t.source() + " line " + std::to_string(t.line(row));
}

Factor collect_levels(const analysis::LongTable& table, const std::string& name) {
  const std::size_t col = table.column(name);
  Factor f{name, {}};
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::string& v = table.cell(r, col);
    if (v.empty() || v == "NA")
      throw DataError(where(table, r) + ", column '" + name + "': missing value");
    if (std::find(f.levels.begin(), f.levels.end(), v) == f.levels.end()) f.levels.push_back(v);
  }
  if (f.levels.size() < 2)
    throw DataError(table.source() + ", column '" + name +
                    "': a factor needs at least two levels, found only '" + f.levels.front() + "'");
  return f;
}

int level_index(const Factor& f, const std::string& value) {
  return int(std::find(f.levels.begin(), f.levels.end(), value) - f.levels.begin());
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

  RmData data;
  for (const auto& name : spec.within) data.within.push_back(collect_levels(table, name));
  for (const auto& name : spec.between) data.between.push_back(collect_levels(table, name));
  data.covariates = spec.covariates;
  data.observed = spec.observed;
  for (const auto& name : spec.observed)
    if (std::find(spec.between.begin(), spec.between.end(), name) == spec.between.end() &&
        std::find(spec.covariates.begin(), spec.covariates.end(), name) == spec.covariates.end())
      throw DataError("observed variable '" + name + "' must be a between factor or a covariate");

  const std::size_t subject_col = table.column(spec.subject);
  const std::vector<double> dv = table.numbers(spec.dv);
  std::vector<std::vector<double>> covariate_columns;
  for (const auto& name : spec.covariates) covariate_columns.push_back(table.numbers(name));
  std::vector<std::size_t> within_cols, between_cols;
  for (const auto& name : spec.within) within_cols.push_back(table.column(name));
  for (const auto& name : spec.between) between_cols.push_back(table.column(name));

  int cells = 1;
  for (const auto& f : data.within) cells *= int(f.levels.size());

  struct Subject {
    std::string id;
    std::size_t first_row;
    std::vector<double> sum;
    std::vector<int> count;
    std::vector<int> between;
    std::vector<double> covariates;
  };
  std::vector<Subject> subjects;
  std::map<std::string, std::size_t> index;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::string& id = table.cell(r, subject_col);
    if (id.empty() || id == "NA")
      throw DataError(where(table, r) + ", column '" + spec.subject + "': missing participant id");
    auto [it, inserted] = index.emplace(id, subjects.size());
    if (inserted) {
      Subject s{id,
                r,
                std::vector<double>(std::size_t(cells), 0.0),
                std::vector<int>(std::size_t(cells), 0),
                {},
                {}};
      for (std::size_t b = 0; b < between_cols.size(); ++b)
        s.between.push_back(level_index(data.between[b], table.cell(r, between_cols[b])));
      for (const auto& column : covariate_columns) s.covariates.push_back(column[r]);
      subjects.push_back(std::move(s));
    }
    Subject& s = subjects[it->second];
    for (std::size_t b = 0; b < between_cols.size(); ++b)
      if (level_index(data.between[b], table.cell(r, between_cols[b])) != s.between[b])
        throw DataError(where(table, r) + ", column '" + spec.between[b] + "': participant " + id +
                        " has more than one value of a between factor");
    for (std::size_t k = 0; k < covariate_columns.size(); ++k)
      if (covariate_columns[k][r] != s.covariates[k])
        throw DataError(where(table, r) + ", column '" + spec.covariates[k] + "': participant " +
                        id + " has more than one value of a covariate");
    int cell = 0, stride = 1;
    for (std::size_t f = 0; f < within_cols.size(); ++f) {
      cell += stride * level_index(data.within[f], table.cell(r, within_cols[f]));
      stride *= int(data.within[f].levels.size());
    }
    s.sum[std::size_t(cell)] += dv[r];
    s.count[std::size_t(cell)] += 1;
  }

  bool averaged = false;
  std::vector<const Subject*> kept;
  for (const Subject& s : subjects) {
    const bool complete = std::all_of(s.count.begin(), s.count.end(), [](int n) { return n > 0; });
    if (!complete) {
      data.dropped_subjects.push_back(s.id);
      continue;
    }
    averaged |= std::any_of(s.count.begin(), s.count.end(), [](int n) { return n > 1; });
    kept.push_back(&s);
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

  const std::size_t n = kept.size();
  data.y.resize(Eigen::Index(n), cells);
  data.covariate_values.resize(Eigen::Index(n), Eigen::Index(spec.covariates.size()));
  for (std::size_t i = 0; i < n; ++i) {
    const Subject& s = *kept[i];
    data.subjects.push_back(s.id);
    data.between_levels.push_back(s.between);
    for (int c = 0; c < cells; ++c)
      data.y(Eigen::Index(i), c) = s.sum[std::size_t(c)] / s.count[std::size_t(c)];
    for (std::size_t k = 0; k < s.covariates.size(); ++k)
      data.covariate_values(Eigen::Index(i), Eigen::Index(k)) = s.covariates[k];
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
