// Where the soft hand's steps spent their time, by part of the solve (StepTimer,
// core/sim/sim_options.h), as `sim bench`, `sim replay` and `simulate` report it.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>

#include "core/sim/step_totals.h"
#include "core/util/json_writer.h"

namespace handlab::cli {

// Part k's name in JSON keys and CSV columns (kStepTimerNames), and for people
// (kStepTimerLabels); k = kStepTimers is the rest of the step.
std::string step_part_name(std::size_t k);
std::string step_part_label(std::size_t k);

// The parts' names, comma separated (for help texts).
std::string step_part_names();

// "ms a step by part: evaluate 0.34, ..., the rest 0.19" over the totals' steps.
void print_step_parts(std::ostream& out, const sim::StepTotals& totals);

// "timer_seconds": each part's seconds over the totals' steps, keyed by its name.
void write_step_parts(util::JsonWriter& json, const sim::StepTotals& totals);

}  // namespace handlab::cli
