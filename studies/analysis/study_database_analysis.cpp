#include "studies/analysis/study_database_analysis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "analysis/report/analysis_output.h"
#include "analysis/stats/descriptives.h"
#include "studies/export/study_export.h"

namespace handlab::studies {
namespace {

// Per cell of `factors`: each participant's mean of `dv`, then their mean and SE, and the
// median and range of the values themselves; over the participants the test analysed (those
// it `left_out`, lacking a cell, are left out here too, so a figure's n is the table's).
std::vector<CellSummary> summarise(const analysis::LongTable& table, const std::string& dv,
                                   const std::vector<std::string>& factors,
                                   const std::vector<std::string>& left_out) {
  const std::size_t subject = table.column("participant");
  const std::vector<double> values = table.numbers(dv);
  std::vector<analysis::LongTable::Codes> codes;
  for (const std::string& f : factors) codes.push_back(table.factor_codes(f));
  // cell -> participant -> values
  std::map<std::vector<int>, std::map<std::string, std::vector<double>>> cells;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    if (std::find(left_out.begin(), left_out.end(), table.cell(r, subject)) != left_out.end())
      continue;
    std::vector<int> key;
    for (const auto& c : codes) key.push_back(c.codes[r]);
    cells[key][table.cell(r, subject)].push_back(values[r]);
  }
  std::vector<CellSummary> out;
  for (const auto& [key, by_subject] : cells) {
    CellSummary s;
    for (std::size_t f = 0; f < factors.size(); ++f)
      s.levels.push_back(codes[f].levels[std::size_t(key[f])]);
    std::vector<double> means, all;
    for (const auto& [id, v] : by_subject) {
      double sum = 0;
      for (double x : v) sum += x;
      means.push_back(sum / double(v.size()));
      all.insert(all.end(), v.begin(), v.end());
    }
    const stats::Descriptives d = stats::describe(means);
    const stats::Descriptives a = stats::describe(all);
    s.n = d.n;
    s.mean = d.mean;
    s.se = d.n > 1 ? d.se : 0.0;
    s.median = a.median;
    s.min = a.min;
    s.max = a.max;
    out.push_back(s);
  }
  return out;
}

}  // namespace

StudyDatabaseAnalysis analyze_study_database(const std::string& path) {
  store::StudyStore store(path);
  StudyDatabaseAnalysis result;
  result.study = store.study();
  const store::StudyInfo& info = result.study;
  std::ostringstream trials, answers;
  write_trials_csv(store, trials, false);  // skipped trials have no time
  write_questionnaire_csv(store, answers);
  const analysis::LongTable trial_table =
      analysis::LongTable::parse_csv(trials.str(), path + " (trials)");
  if (trial_table.rows() == 0)
    throw std::runtime_error(path + " has no trial results to analyse yet");

  analysis::AnalysisRequest times;
  times.design.subject = "participant";
  times.design.dv = "completion_time_s";
  times.design.within = info.factors;
  times.design.within.push_back("repetition");
  result.completion_time = analysis::run_analysis(trial_table, times);
  const std::vector<std::string>& left_out = result.completion_time.dropped_subjects;
  result.time_by_condition = summarise(trial_table, "completion_time_s", info.factors, left_out);
  for (const std::string& f : info.factors)
    result.time_by_repetition.emplace_back(
        f, summarise(trial_table, "completion_time_s", {f, "repetition"}, left_out));

  // Before anyone has reached the questionnaire its export is the header alone: the times
  // are analysed all the same.
  const std::string answer_text = answers.str();
  const std::size_t header_end = answer_text.find('\n');
  if (header_end != std::string::npos && header_end + 1 < answer_text.size()) {
    const analysis::LongTable items =
        analysis::LongTable::parse_csv(answer_text, path + " (questionnaire)");
    analysis::AnalysisRequest request;
    request.design.subject = "participant";
    request.design.within = info.factors;
    const std::vector<std::string>& columns = items.columns();
    const auto first_item = std::find(columns.begin(), columns.end(), "repetition") + 1;
    request.nonparametric_items.assign(first_item, columns.end());
    result.questionnaire = analysis::run_analysis(items, request);
    for (const std::string& item : request.nonparametric_items) {
      std::vector<std::string> item_left_out;
      for (const auto& f : result.questionnaire->friedman)
        if (f.dv == item) item_left_out = f.dropped_subjects;
      result.items_by_condition.emplace_back(item,
                                             summarise(items, item, info.factors, item_left_out));
    }
  }
  return result;
}

void write_study_analysis_text(const StudyDatabaseAnalysis& a, const std::string& path,
                               std::ostream& out) {
  out << "Study " << a.study.name << " (" << path << "): completion time\n\n";
  analysis::write_text(a.completion_time, out);
  if (a.questionnaire) {
    out << "\nQuestionnaire\n\n";
    analysis::write_text(*a.questionnaire, out);
  }
}

void write_study_analysis_json(const StudyDatabaseAnalysis& a, std::ostream& out) {
  out << "{\"completion_time\": ";
  analysis::write_json(a.completion_time, out);
  out << ", \"questionnaire\": ";
  if (a.questionnaire)
    analysis::write_json(*a.questionnaire, out);
  else
    out << "null";
  out << "}\n";
}

}  // namespace handlab::studies
