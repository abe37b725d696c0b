#include "studies/power/pilot_model.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "analysis/data/long_table.h"
#include "analysis/stats/rm_data.h"
#include "studies/export/study_export.h"
#include "studies/protocol/protocol_store.h"

namespace handlab::studies {

power::PowerDesign power_design(const Protocol& protocol) {
  power::PowerDesign d;
  for (const Factor& f : protocol.factors) {
    stats::Factor factor{f.name, {}};
    for (const Level& l : f.levels) factor.levels.push_back(l.name);
    d.factors.push_back(factor);
  }
  d.repetitions = protocol.blocks;
  return d;
}

namespace {

// Columns of `from`'s cells in `to`'s cell order (the data name levels in order of appearance).
Eigen::MatrixXd in_design_order(const stats::RmData& from, const power::PowerDesign& to) {
  const std::vector<stats::Factor> within = to.within();
  Eigen::MatrixXd out(from.y.rows(), to.cells());
  for (int c = 0; c < from.cells(); ++c) {
    const std::vector<int> levels = from.cell_levels(c);
    int target = 0, stride = 1;
    for (std::size_t f = 0; f < within.size(); ++f) {
      const std::string& level = from.within[f].levels[std::size_t(levels[f])];
      const auto& names = within[f].levels;
      const auto at = std::find(names.begin(), names.end(), level);
      if (at == names.end())
        throw std::runtime_error("the pilot's " + within[f].name + " level '" + level +
                                 "' is not in the protocol");
      target += int(at - names.begin()) * stride;
      stride *= int(names.size());
    }
    out.col(target) = from.y.col(c);
  }
  return out;
}

}  // namespace

power::PowerModel estimate_from_pilot(const std::string& db_path, const Protocol& protocol) {
  const power::PowerDesign design = power_design(protocol);
  store::StudyStore store(db_path, store::StudyStore::Access::kReadOnly);
  const Protocol pilot = stored_protocol(store);
  if (power_design(pilot).within().size() != design.within().size() ||
      power_design(pilot).cells() != design.cells())
    throw std::runtime_error(
        db_path + ": the pilot's design (" + std::to_string(power_design(pilot).cells()) +
        " cells) is not the protocol's (" + std::to_string(design.cells()) + ")");
  std::ostringstream trials, answers;
  write_trials_csv(store, trials, false);
  write_questionnaire_csv(store, answers);
  const analysis::LongTable table =
      analysis::LongTable::parse_csv(trials.str(), db_path + " trials");
  stats::RmDesignSpec spec;
  spec.subject = "participant";
  spec.dv = "completion_time_s";
  for (const stats::Factor& f : design.within()) spec.within.push_back(f.name);
  const stats::RmData data = stats::prepare_rm_data(table, spec);
  // Planned results the pilot lacks: cells of the participants it has, without a time.
  const double planned =
      double(data.subjects.size() + data.dropped_subjects.size()) * design.cells();
  const double missing = std::max(0.0, 1.0 - double(table.rows()) / planned);
  std::vector<power::PilotItem> items;
  if (!protocol.items.empty() && answers.str().find('\n') + 1 < answers.str().size()) {
    const analysis::LongTable a =
        analysis::LongTable::parse_csv(answers.str(), db_path + " questionnaire");
    for (const QuestionnaireItem& q : protocol.items) {
      stats::RmDesignSpec item_spec;
      item_spec.subject = "participant";
      item_spec.dv = q.id;
      for (const stats::Factor& f : design.factors) item_spec.within.push_back(f.name);
      const stats::RmData item = stats::prepare_rm_data(a, item_spec);
      power::PowerDesign conditions = design;
      conditions.repetitions = 1;
      items.push_back({q.id, protocol.scale_points, in_design_order(item, conditions)});
    }
  }
  power::PowerModel model =
      power::estimate_power_model(design, in_design_order(data, design), missing, items);
  model.notes.insert(model.notes.begin(), "pilot: " + db_path + ", " +
                                              std::to_string(data.subjects.size()) +
                                              " participants with every cell, " +
                                              std::to_string(int(100 * missing + 0.5)) +
                                              " % of planned results missing");
  return model;
}

}  // namespace handlab::studies
