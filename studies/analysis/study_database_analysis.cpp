#include "studies/analysis/study_database_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "analysis/report/analysis_output.h"
#include "analysis/stats/descriptives.h"
#include "core/util/json_writer.h"
#include "studies/export/study_export.h"
#include "studies/protocol/protocol_store.h"

namespace handlab::studies {
namespace {

using LongTableCodes = analysis::LongTable::Codes;

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// Per cell of `factors`: each participant's mean of `dv`, then their mean, SD, SE and median,
// the within-participant SE, and the range of the values themselves; over the participants
// the test analysed (those it `left_out`, lacking a cell, are left out here too, so a
// figure's n is the table's).
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
    if (contains(left_out, table.cell(r, subject))) continue;
    std::vector<int> key;
    for (const auto& c : codes) key.push_back(c.codes[r]);
    cells[key][table.cell(r, subject)].push_back(values[r]);
  }
  auto mean_of = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / double(v.size());
  };
  // Cousineau-Morey: participants with every cell of the summary, each moved to the grand
  // mean; the SE of the moved means, times sqrt(C / (C - 1)).
  std::map<std::string, double> own_mean;  // a participant's mean over the cells
  {
    std::map<std::string, std::pair<double, int>> sums;
    for (const auto& [key, by_subject] : cells)
      for (const auto& [id, v] : by_subject) {
        sums[id].first += mean_of(v);
        sums[id].second += 1;
      }
    for (const auto& [id, s] : sums)
      if (s.second == int(cells.size())) own_mean[id] = s.first / s.second;
  }
  double grand = 0;
  for (const auto& [id, m] : own_mean) grand += m / double(own_mean.size());
  const double morey =
      cells.size() > 1 ? std::sqrt(double(cells.size()) / double(cells.size() - 1)) : 1.0;

  std::vector<CellSummary> out;
  for (const auto& [key, by_subject] : cells) {
    CellSummary s;
    for (std::size_t f = 0; f < factors.size(); ++f)
      s.levels.push_back(codes[f].levels[std::size_t(key[f])]);
    std::vector<double> means, all, moved;
    for (const auto& [id, v] : by_subject) {
      means.push_back(mean_of(v));
      all.insert(all.end(), v.begin(), v.end());
      if (const auto own = own_mean.find(id); own != own_mean.end())
        moved.push_back(means.back() - own->second + grand);
    }
    const stats::Descriptives d = stats::describe(means);
    const stats::Descriptives a = stats::describe(all);
    s.n = d.n;
    s.mean = d.mean;
    s.sd = d.n > 1 ? d.sd : 0.0;
    s.se = d.n > 1 ? d.se : 0.0;
    s.median = d.median;
    s.se_within = moved.size() > 1 ? morey * stats::describe(moved).se : s.se;
    s.min = a.min;
    s.max = a.max;
    out.push_back(s);
  }
  return out;
}

// Where a level comes in the protocol's order of its factor's levels; a factor the protocol
// does not list (the repetition) by the level's number.
double level_rank(const Protocol& protocol, const std::string& factor, const std::string& level) {
  const int index = protocol.factor_index(factor);
  if (index < 0) return std::atof(level.c_str());
  const auto& levels = protocol.factors[std::size_t(index)].levels;
  return double(
      std::find_if(levels.begin(), levels.end(), [&](const Level& l) { return l.name == level; }) -
      levels.begin());
}

// Cells in the protocol's order of levels (repetitions by number), not the data's.
void protocol_order(std::vector<CellSummary>& cells, const Protocol& protocol,
                    const std::vector<std::string>& factors) {
  auto rank = [&](const CellSummary& c) {
    std::vector<double> key;
    for (std::size_t f = 0; f < factors.size() && f < c.levels.size(); ++f)
      key.push_back(level_rank(protocol, factors[f], c.levels[f]));
    return key;
  };
  std::stable_sort(cells.begin(), cells.end(),
                   [&](const CellSummary& a, const CellSummary& b) { return rank(a) < rank(b); });
}

// Each analysed participant's mean time per level of `factor`, at their hand length.
std::vector<HandLengthPoint> by_hand_length(const analysis::LongTable& table,
                                            const std::string& factor,
                                            const std::vector<std::string>& left_out) {
  const std::size_t subject = table.column("participant");
  const std::size_t level = table.column(factor);
  const std::vector<double> hand = table.numbers("hand_length");
  const std::vector<double> time = table.numbers("completion_time_s");
  std::map<std::pair<std::string, std::string>, std::pair<double, int>> sums;
  std::map<std::string, double> hand_of;
  std::vector<std::pair<std::string, std::string>> order;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    if (contains(left_out, table.cell(r, subject))) continue;
    const auto key = std::pair(table.cell(r, subject), table.cell(r, level));
    if (!sums.count(key)) order.push_back(key);
    sums[key].first += time[r];
    sums[key].second += 1;
    hand_of[key.first] = hand[r];
  }
  std::vector<HandLengthPoint> out;
  for (const auto& key : order)
    out.push_back(
        {key.first, key.second, 100.0 * hand_of[key.first], sums[key].first / sums[key].second});
  return out;
}

std::vector<std::pair<std::string, int>> counts(const std::vector<std::string>& values) {
  std::vector<std::pair<std::string, int>> out;
  for (const std::string& v : values) {
    auto at = std::find_if(out.begin(), out.end(), [&](const auto& c) { return c.first == v; });
    if (at == out.end())
      out.emplace_back(v, 1);
    else
      ++at->second;
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  return out;
}

ParticipantSummary summarise_participants(const std::vector<store::Participant>& people,
                                          const Protocol& protocol) {
  ParticipantSummary s;
  for (const BetweenFactor& f : protocol.between) {
    std::vector<std::pair<std::string, int>> levels;
    for (const BetweenLevel& l : f.levels) {
      int n = 0;
      for (const store::Participant& p : people)
        n +=
            std::count(p.between_levels.begin(), p.between_levels.end(), std::pair{f.name, l.name});
      levels.emplace_back(l.name, n);
    }
    s.groups.emplace_back(f.name, std::move(levels));
  }
  s.enrolled = int(people.size());
  std::vector<double> ages, hands;
  std::vector<std::string> sex, handedness, vr;
  for (const store::Participant& p : people) {
    s.simulated += p.simulated ? 1 : 0;
    if (p.age > 0) ages.push_back(p.age);
    if (p.hand_length > 0) hands.push_back(100.0 * p.hand_length);
    sex.push_back(p.sex);
    handedness.push_back(p.handedness);
    vr.push_back(p.vr_experience);
  }
  if (!ages.empty()) {
    const stats::Descriptives d = stats::describe(ages);
    s.age_n = d.n;
    s.age_mean = d.mean;
    s.age_sd = d.n > 1 ? d.sd : 0.0;
    s.age_min = d.min;
    s.age_max = d.max;
  }
  if (!hands.empty()) {
    const stats::Descriptives d = stats::describe(hands);
    s.hand_cm_mean = d.mean;
    s.hand_cm_sd = d.n > 1 ? d.sd : 0.0;
    s.hand_cm_min = d.min;
    s.hand_cm_max = d.max;
  }
  s.sex = counts(sex);
  s.handedness = counts(handedness);
  s.vr_experience = counts(vr);
  return s;
}

DataQuality assess_data(store::StudyStore& store, const Protocol& protocol) {
  DataQuality q;
  q.by_condition = condition_outcomes(store, protocol);
  q.losses = cube_losses(store, protocol);
  for (const ConditionOutcome& c : q.by_condition) {
    q.planned += c.planned;
    q.completed += c.completed;
    q.timeouts += c.timeouts;
    q.skipped += c.skipped;
    q.not_run += c.not_run;
    q.attempts_aborted += c.attempts_aborted;
    q.attempts_redone += c.attempts_redone;
    q.practice_run += c.practice_run;
  }
  q.frames = store.frame_count();
  return q;
}

// The follow-up with one participant variable, over the participants of the main analysis.
ParticipantVariableAnalysis with_variable(const analysis::LongTable& table,
                                          const std::vector<std::string>& factors,
                                          const std::string& variable, bool between) {
  ParticipantVariableAnalysis out;
  out.variable = variable;
  out.between = between;
  const std::size_t subject = table.column("participant");
  const std::size_t column = table.column(variable);
  std::map<std::string, std::string> value_of;
  for (std::size_t r = 0; r < table.rows(); ++r)
    value_of[table.cell(r, subject)] = table.cell(r, column);
  std::set<std::string> distinct;
  for (const auto& [id, v] : value_of) distinct.insert(v);
  if (distinct.size() < 2) {
    out.not_computed = "every participant analysed has the same " + variable;
    return out;
  }
  // A covariate takes one df and a between factor one per level beyond the first: the error
  // term needs participants left over.
  const int parameters = between ? int(distinct.size()) : 2;
  if (int(value_of.size()) <= parameters) {
    out.not_computed = "too few participants (" + std::to_string(value_of.size()) + ") for " +
                       variable + " as a " +
                       (between ? "between-participants factor" : "covariate");
    return out;
  }
  analysis::AnalysisRequest request;
  request.design.subject = "participant";
  request.design.dv = "completion_time_s";
  request.design.within = factors;
  (between ? request.design.between : request.design.covariates).push_back(variable);
  request.r_level_names = false;
  request.posthoc = {};
  try {
    out.result = analysis::run_analysis(table, request);
  } catch (const analysis::DataError& e) {
    out.not_computed = e.what();
  }
  return out;
}

void write_summary(util::JsonWriter& json, const CellSummary& c,
                   const std::vector<std::string>& factors) {
  json.begin_object();
  json.key("cell").begin_object();
  for (std::size_t f = 0; f < factors.size() && f < c.levels.size(); ++f)
    json.field(factors[f], c.levels[f]);
  json.end_object();
  json.field("n", c.n).field("mean", c.mean).field("sd", c.sd).field("se", c.se);
  json.field("se_within", c.se_within).field("median", c.median);
  json.field("min", c.min).field("max", c.max).end_object();
}

// A table of the study's exports with every factor's levels in the protocol's order, so a
// contrast reads the same way in every study of the protocol, whoever ran first.
analysis::LongTable in_protocol_order(const std::string& csv, const std::string& name,
                                      const Protocol& protocol) {
  analysis::LongTable table = analysis::LongTable::parse_csv(csv, name);
  const std::vector<std::string>& columns = table.columns();
  auto has = [&](const std::string& c) {
    return std::find(columns.begin(), columns.end(), c) != columns.end();
  };
  for (const Factor& f : protocol.factors) {
    if (!has(f.name)) continue;
    std::vector<std::string> order;
    for (const Level& l : f.levels) order.push_back(l.name);
    table.order_levels(f.name, order);
  }
  if (has("repetition")) {  // 1, 2, ... as numbers, not as text in order of appearance
    std::vector<std::string> order;
    for (int r = 1; r <= protocol.blocks; ++r) order.push_back(std::to_string(r));
    table.order_levels("repetition", order);
  }
  for (const BetweenFactor& f : protocol.between) {
    if (!has(f.name)) continue;
    std::vector<std::string> order;
    for (const BetweenLevel& l : f.levels) order.push_back(l.name);
    table.order_levels(f.name, order);
  }
  return table;
}

}  // namespace

StudyDatabaseAnalysis analyze_study_database(const std::string& path) {
  store::StudyStore store(path, store::StudyStore::Access::kReadOnly);
  StudyDatabaseAnalysis result;
  result.study = store.study();
  result.completeness = store.completeness();
  result.protocol = stored_protocol(store);
  const store::StudyInfo& info = result.study;
  const std::vector<store::Participant> people = store.participants();
  result.participants = summarise_participants(people, result.protocol);
  result.quality = assess_data(store, result.protocol);

  std::ostringstream trials, answers;
  write_trials_csv(store, trials, false);  // skipped trials have no time
  write_questionnaire_csv(store, answers);
  // A header alone (no trial has a result yet) is a table of no rows.
  auto has_rows = [](const std::string& csv) {
    const std::size_t end = csv.find('\n');
    return end != std::string::npos && end + 1 < csv.size();
  };
  const std::string trial_text = trials.str();
  std::vector<std::string> left_out;
  if (!has_rows(trial_text)) {
    result.completion_time_not_computed = "no scheduled trial has a completion time yet";
    result.time_without_timeouts.not_computed = result.completion_time_not_computed;
    result.success.not_computed = result.completion_time_not_computed;
  } else {
    const analysis::LongTable trial_table =
        in_protocol_order(trial_text, "trials", result.protocol);
    std::vector<std::string> between;
    for (const BetweenFactor& f : result.protocol.between) between.push_back(f.name);
    result.time_without_timeouts = time_without_timeouts(trial_table, info.factors, between);
    result.success = success_rates(trial_table, info.factors);
    analysis::AnalysisRequest times;
    times.design.subject = "participant";
    times.design.dv = "completion_time_s";
    times.design.within = info.factors;
    times.design.within.push_back("repetition");
    times.design.between = between;
    times.r_level_names = false;
    // A condition nobody has a time in: say which, not only that the design is incomplete.
    std::vector<std::string> missing;
    {
      std::vector<LongTableCodes> codes;
      for (const std::string& f : info.factors) codes.push_back(trial_table.factor_codes(f));
      for (const Condition& c : result.protocol.conditions()) {
        bool found = false;
        for (std::size_t r = 0; r < trial_table.rows() && !found; ++r) {
          found = true;
          for (std::size_t f = 0; f < codes.size(); ++f)
            found = found && codes[f].levels[std::size_t(codes[f].codes[r])] ==
                                 result.protocol.factors[f].levels[std::size_t(c.levels[f])].name;
        }
        if (!found) missing.push_back(c.label);
      }
    }
    try {
      if (!missing.empty()) {
        std::string list;
        for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
        throw analysis::DataError("condition " + list +
                                  " has no completion time yet (every trial of it skipped or "
                                  "not run)");
      }
      analysis::AnalysisReport report = analysis::run_analysis(trial_table, times);
      if (report.n_subjects < 2) {
        result.completion_time_not_computed =
            "a repeated-measures ANOVA needs two participants or more with a time in every "
            "condition and repetition; " +
            std::to_string(report.n_subjects) + " has one";
      } else {
        result.completion_time = std::move(report);
      }
    } catch (const analysis::DataError& e) {
      result.completion_time_not_computed = e.what();
    }
    if (result.completion_time) {
      left_out = result.completion_time->dropped_subjects;
      result.participants.analysed = result.completion_time->n_subjects;
      for (const std::string& id : left_out)
        result.quality.left_out.emplace_back(
            id, "completion time: lacks a time in some condition and repetition");
    }
    result.time_by_condition = summarise(trial_table, "completion_time_s", info.factors, left_out);
    protocol_order(result.time_by_condition, result.protocol, info.factors);
    for (const std::string& f : info.factors) {
      result.time_by_repetition.emplace_back(
          f, summarise(trial_table, "completion_time_s", {f, "repetition"}, left_out));
      protocol_order(result.time_by_repetition.back().second, result.protocol, {f, "repetition"});
      result.time_by_hand_length.emplace_back(f, by_hand_length(trial_table, f, left_out));
      // Levels in the protocol's order, as the other figures have them.
      auto& points = result.time_by_hand_length.back().second;
      std::stable_sort(points.begin(), points.end(), [&](const auto& a, const auto& b) {
        return level_rank(result.protocol, f, a.level) < level_rank(result.protocol, f, b.level);
      });
    }
    if (result.completion_time) {
      const analysis::LongTable analysed = trial_table.without("participant", left_out);
      result.participant_variables.push_back(with_variable(analysed, info.factors, "age", false));
      result.participant_variables.push_back(
          with_variable(analysed, info.factors, "hand_length", false));
      result.participant_variables.push_back(
          with_variable(analysed, info.factors, "vr_experience", true));
    }
  }

  // Before anyone has reached the questionnaire its export is the header alone.
  const std::string answer_text = answers.str();
  if (result.protocol.items.empty()) {
    result.questionnaire_not_computed = "the protocol asks no questions";
  } else if (!has_rows(answer_text)) {
    result.questionnaire_not_computed = "no questionnaire has been answered yet";
  } else {
    const analysis::LongTable items =
        in_protocol_order(answer_text, "questionnaire", result.protocol);
    analysis::AnalysisRequest request;
    request.design.subject = "participant";
    request.design.within = info.factors;
    const std::vector<std::string>& columns = items.columns();
    const auto first_item = std::find(columns.begin(), columns.end(), "repetition") + 1;
    request.nonparametric_items.assign(first_item, columns.end());
    try {
      result.questionnaire = analysis::run_analysis(items, request);
    } catch (const analysis::DataError& e) {
      result.questionnaire_not_computed = e.what();
    }
    if (result.questionnaire) {
      for (const std::string& item : request.nonparametric_items) {
        std::vector<std::string> item_left_out;
        for (const auto& f : result.questionnaire->friedman)
          if (f.dv == item) item_left_out = f.dropped_subjects;
        for (const std::string& id : item_left_out)
          result.quality.left_out.emplace_back(id, item + ": lacks an answer in some condition");
        result.items_by_condition.emplace_back(item,
                                               summarise(items, item, info.factors, item_left_out));
        protocol_order(result.items_by_condition.back().second, result.protocol, info.factors);
      }
    }
  }
  return result;
}

void write_study_analysis_text(const StudyDatabaseAnalysis& a, const std::string& path,
                               std::ostream& out) {
  out << "Study " << a.study.name << " (" << path << ")\n";
  if (a.completeness.partial())
    out << "Partial study: " << a.completeness.describe()
        << "; its results are not the study's until the missing parts are merged in\n";
  out << "\nScheduled trials (practice excluded)\n";
  auto outcome_line = [&](const std::string& what, int planned, int completed, int timeouts,
                          int skipped, int not_run) {
    out << "  " << what << ": " << planned << " planned, " << completed << " completed, "
        << timeouts << " timed out, " << skipped << " skipped, " << not_run << " not run\n";
  };
  for (const ConditionOutcome& c : a.quality.by_condition)
    outcome_line(c.condition, c.planned, c.completed, c.timeouts, c.skipped, c.not_run);
  const DataQuality& q = a.quality;
  outcome_line("all", q.planned, q.completed, q.timeouts, q.skipped, q.not_run);
  out << "\nCompletion time\n\n";
  if (a.completion_time)
    analysis::write_text(*a.completion_time, out);
  else
    out << "Not computed: " << a.completion_time_not_computed << "\n";
  for (const auto& [title, way] :
       {std::pair{"Completion time, the timed-out trials left out", &a.time_without_timeouts},
        std::pair{"Success (completed of the trials that ended) per condition", &a.success}}) {
    out << "\n" << title << "\n\n";
    if (way->result)
      analysis::write_text(*way->result, out);
    else
      out << "Not computed: " << way->not_computed << "\n";
  }
  for (const ParticipantVariableAnalysis& v : a.participant_variables) {
    out << "\nWith " << v.variable << " as a "
        << (v.between ? "between-participants factor" : "covariate")
        << " (repetitions averaged)\n\n";
    if (v.result)
      analysis::write_text(*v.result, out);
    else
      out << "Not computed: " << v.not_computed << "\n";
  }
  out << "\nQuestionnaire\n\n";
  if (a.questionnaire)
    analysis::write_text(*a.questionnaire, out);
  else
    out << "Not computed: " << a.questionnaire_not_computed << "\n";
}

void write_study_analysis_json(const StudyDatabaseAnalysis& a, std::ostream& out) {
  out << "{\n\"study\": ";
  {
    util::JsonWriter json(out);
    json.begin_object().field("name", a.study.name).field("title", a.protocol.title);
    json.field("protocol_sha256", a.study.protocol_sha256).field("created_at", a.study.created_at);
    json.key("factors").string_array(a.study.factors);
    json.field("blocks", a.protocol.blocks)
        .field("practice_per_condition", a.protocol.practice_per_condition)
        .field("timeout_s", a.protocol.timeout_s);
    json.field("partial", a.completeness.partial())
        .field("planned_participants", a.completeness.planned);
    json.key("missing_places").begin_array();
    for (int place : a.completeness.missing_places) json.value(place + 1);
    json.end_array();
    json.end_object();
  }
  out << ",\n\"participants\": ";
  {
    const ParticipantSummary& p = a.participants;
    util::JsonWriter json(out);
    json.begin_object().field("enrolled", p.enrolled).field("simulated", p.simulated);
    json.field("analysed", p.analysed).field("age_n", p.age_n);
    json.field("age_mean", p.age_mean).field("age_sd", p.age_sd);
    json.field("age_min", p.age_min).field("age_max", p.age_max);
    json.field("hand_length_cm_mean", p.hand_cm_mean).field("hand_length_cm_sd", p.hand_cm_sd);
    json.field("hand_length_cm_min", p.hand_cm_min).field("hand_length_cm_max", p.hand_cm_max);
    for (const auto& [key, list] :
         {std::pair{"sex", &p.sex}, std::pair{"handedness", &p.handedness},
          std::pair{"vr_experience", &p.vr_experience}}) {
      json.key(key).begin_object();
      for (const auto& [value, count] : *list) json.field(value, count);
      json.end_object();
    }
    json.key("groups").begin_object();
    for (const auto& [factor, levels] : p.groups) {
      json.key(factor).begin_object();
      for (const auto& [level, count] : levels) json.field(level, count);
      json.end_object();
    }
    json.end_object();
    json.end_object();
  }
  out << ",\n\"data_quality\": ";
  {
    const DataQuality& q = a.quality;
    util::JsonWriter json(out);
    json.begin_object().field("planned", q.planned).field("completed", q.completed);
    json.field("timeouts", q.timeouts).field("skipped", q.skipped).field("not_run", q.not_run);
    json.field("attempts_aborted", q.attempts_aborted).field("attempts_redone", q.attempts_redone);
    json.field("practice_run", q.practice_run).field("frames", static_cast<long long>(q.frames));
    json.key("by_condition").begin_array();
    for (const ConditionOutcome& c : q.by_condition) write_condition_outcome(json, c);
    json.end_array().key("cube_losses");
    write_cube_losses(json, q.losses);
    json.key("left_out").begin_array();
    for (const auto& [id, why] : q.left_out)
      json.begin_object().field("participant", id).field("why", why).end_object();
    json.end_array().end_object();
  }
  out << ",\n\"completion_time\": ";
  if (a.completion_time)
    analysis::write_json(*a.completion_time, out);
  else
    out << "null";
  out << ",\n\"completion_time_not_computed\": ";
  util::JsonWriter(out).value(a.completion_time_not_computed);
  for (const auto& [key, way] :
       {std::pair{"completion_time_without_timeouts", &a.time_without_timeouts},
        std::pair{"success", &a.success}}) {
    out << ",\n\"" << key << "\": ";
    if (way->result)
      analysis::write_json(*way->result, out);
    else
      out << "null";
    out << ",\n\"" << key << "_not_computed\": ";
    util::JsonWriter(out).value(way->not_computed);
  }
  out << ",\n\"condition_descriptives\": ";
  {
    util::JsonWriter json(out);
    json.begin_array();
    for (const CellSummary& c : a.time_by_condition) write_summary(json, c, a.study.factors);
    json.end_array();
  }
  out << ",\n\"participant_variables\": [";
  for (std::size_t i = 0; i < a.participant_variables.size(); ++i) {
    const ParticipantVariableAnalysis& v = a.participant_variables[i];
    out << (i ? ",\n" : "\n") << "{\"variable\": ";
    util::JsonWriter(out).value(v.variable);
    out << ", \"between\": " << (v.between ? "true" : "false") << ", \"not_computed\": ";
    util::JsonWriter(out).value(v.not_computed);
    out << ", \"analysis\": ";
    if (v.result)
      analysis::write_json(*v.result, out);
    else
      out << "null";
    out << "}";
  }
  out << "],\n\"questionnaire\": ";
  if (a.questionnaire)
    analysis::write_json(*a.questionnaire, out);
  else
    out << "null";
  out << ",\n\"questionnaire_not_computed\": ";
  util::JsonWriter(out).value(a.questionnaire_not_computed);
  out << "\n}\n";
}

}  // namespace handlab::studies
