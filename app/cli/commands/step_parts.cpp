#include "app/cli/commands/step_parts.h"

#include <algorithm>

#include "core/sim/sim_options.h"

namespace handlab::cli {

std::string step_part_name(std::size_t k) {
  return k < sim::kStepTimers ? sim::kStepTimerNames[k] : "rest";
}

std::string step_part_names() {
  std::string names;
  for (const char* name : sim::kStepTimerNames)
    names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

std::string step_part_label(std::size_t k) {
  return k < sim::kStepTimers ? sim::kStepTimerLabels[k] : "the rest";
}

void print_step_parts(std::ostream& out, const sim::StepTotals& totals) {
  const double steps = double(std::max(1L, totals.steps));
  double timed = 0.0;
  out << "ms a step by part:";
  for (std::size_t k = 0; k < sim::kStepTimers; ++k) {
    out << (k ? ", " : " ") << step_part_label(k) << ' '
        << 1000.0 * totals.timer_seconds[k] / steps;
    timed += totals.timer_seconds[k];
  }
  out << ", " << step_part_label(sim::kStepTimers) << ' '
      << 1000.0 * std::max(0.0, totals.seconds - timed) / steps << '\n';
}

void write_step_parts(util::JsonWriter& json, const sim::StepTotals& totals) {
  json.key("timer_seconds").begin_object();
  for (std::size_t k = 0; k < sim::kStepTimers; ++k)
    json.field(sim::kStepTimerNames[k], totals.timer_seconds[k]);
  json.end_object();
}

}  // namespace handlab::cli
