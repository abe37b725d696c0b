#include "studies/analysis/timeout_analyses.h"

#include <map>
#include <sstream>

#include "core/util/csv.h"

namespace handlab::studies {

OutcomeAnalysis time_without_timeouts(const analysis::LongTable& trials,
                                      const std::vector<std::string>& factors,
                                      const std::vector<std::string>& between) {
  OutcomeAnalysis out;
  const analysis::LongTable completed = trials.without("outcome", {"timeout"});
  if (completed.rows() == 0) {
    out.not_computed = "no trial was completed";
    return out;
  }
  analysis::AnalysisRequest request;
  request.design.subject = "participant";
  request.design.dv = "completion_time_s";
  request.design.within = factors;
  request.design.within.push_back("repetition");
  request.design.between = between;
  request.r_level_names = false;
  try {
    analysis::AnalysisReport report = analysis::run_analysis(completed, request);
    if (report.n_subjects < 2)
      out.not_computed = std::to_string(report.n_subjects) +
                         " participant(s) completed a trial in every condition and repetition; "
                         "a repeated-measures ANOVA needs two or more";
    else
      out.result = std::move(report);
  } catch (const analysis::DataError& e) {
    out.not_computed = e.what();
  }
  return out;
}

OutcomeAnalysis success_rates(const analysis::LongTable& trials,
                              const std::vector<std::string>& factors) {
  OutcomeAnalysis out;
  const std::size_t subject = trials.column("participant");
  const std::size_t outcome = trials.column("outcome");
  std::vector<std::size_t> columns;
  for (const std::string& f : factors) columns.push_back(trials.column(f));
  // participant and levels -> completed, ended; in the order of first appearance
  std::map<std::vector<std::string>, std::pair<int, int>> cells;
  std::vector<std::vector<std::string>> order;
  for (std::size_t r = 0; r < trials.rows(); ++r) {
    std::vector<std::string> key = {trials.cell(r, subject)};
    for (std::size_t c : columns) key.push_back(trials.cell(r, c));
    auto [at, added] = cells.try_emplace(key, 0, 0);
    if (added) order.push_back(key);
    at->second.first += trials.cell(r, outcome) == "success" ? 1 : 0;
    at->second.second += 1;
  }
  std::ostringstream csv;
  csv << "participant";
  for (const std::string& f : factors) csv << ',' << util::csv_field(f);
  csv << ",success_rate\n";
  for (const auto& key : order) {
    for (std::size_t i = 0; i < key.size(); ++i) csv << (i ? "," : "") << util::csv_field(key[i]);
    const auto [completed, ended] = cells.at(key);
    csv << ',' << util::format_number(double(completed) / double(ended)) << '\n';
  }
  analysis::AnalysisRequest request;
  request.design.subject = "participant";
  request.design.within = factors;
  request.nonparametric_items = {"success_rate"};
  try {
    analysis::LongTable rates = analysis::LongTable::parse_csv(csv.str(), "success rates");
    for (const std::string& f : factors) rates.order_levels(f, trials.factor_codes(f).levels);
    out.result = analysis::run_analysis(rates, request);
  } catch (const analysis::DataError& e) {
    out.not_computed = e.what();
  }
  return out;
}

}  // namespace handlab::studies
