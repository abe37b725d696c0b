// What became of each condition's trials, as the analysis (`analyze --db`), `simulate` and
// `replications` count them: a scheduled trial (practice excluded) by its last attempt that
// ended, completed, timed out or skipped; not run when none did.
#pragma once

#include <string>
#include <vector>

#include "core/store/study_store.h"
#include "core/util/json_writer.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

struct ConditionOutcome {
  std::string condition;  // the protocol's label ("naive-fine")
  int planned = 0, completed = 0, timeouts = 0, skipped = 0, not_run = 0;
  double mean_time_s = 0.0;   // of the completed
  int grasps = 0, drops = 0;  // of the last attempts
  // Attempts of the scheduled trials that were aborted or redone; practice trials run.
  int attempts_aborted = 0, attempts_redone = 0, practice_run = 0;
};

// In the protocol's order of conditions, over every participant the store holds.
std::vector<ConditionOutcome> condition_outcomes(store::StudyStore& store,
                                                 const Protocol& protocol);

// One object: condition, planned, completed, timeouts, skipped, not_run, success_rate
// (completed of planned; null when none was), mean_time_s, grasps, drops (`analyze --db`'s
// data_quality, `replications`); the fields alone into an object the caller has begun (`simulate`,
// which adds its own keys).
void write_condition_outcome(util::JsonWriter& json, const ConditionOutcome& outcome);
void write_condition_outcome_fields(util::JsonWriter& json, const ConditionOutcome& outcome);

}  // namespace handlab::studies
