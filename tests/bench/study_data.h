// Synthetic completion times for the study's design (Manipulation x Strategy x Repetition),
// the same for a given N and seed on every machine.
#pragma once

#include <string>

#include "analysis/data/long_table.h"

namespace handlab::bench {

std::string synthetic_study_csv(int participants, unsigned seed);
analysis::LongTable synthetic_study_table(int participants, unsigned seed);

}  // namespace handlab::bench
