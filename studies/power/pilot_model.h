// The power analysis's design from a protocol, and its model estimated from a pilot study's
// database (`handlab-cli power --pilot DB`): completion times per participant and cell (the
// protocol's conditions x repetition, as `analyze --db` analyses them), the share of planned
// trials without a result, and the questionnaire's answers per condition.
#pragma once

#include <string>

#include "analysis/power/power_model.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

power::PowerDesign power_design(const Protocol& protocol);

// Throws std::runtime_error when the pilot's factors differ from the protocol's, or when
// fewer than three participants have a time in every cell.
power::PowerModel estimate_from_pilot(const std::string& db_path, const Protocol& protocol);

}  // namespace handlab::studies
