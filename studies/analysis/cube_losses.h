// How often a study's trials lost the cube, as the trials' records count it: dropped, the cube
// came to rest out of B at least once; grasped again, no drop but more than one grasp (the
// pinch broken and the cube caught or picked up before it rested). Over the scheduled trials
// that were run (completed or timed out; practice and skipped trials excluded), per condition
// and per repetition (`replications`, `analyze --db`'s JSON).
#pragma once

#include <string>
#include <vector>

#include "core/store/study_store.h"
#include "core/util/json_writer.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

struct LossCount {
  std::string label;  // the condition's ("naive-fine") or the repetition's ("1")
  int trials = 0, dropped = 0, grasped_again = 0;
};

struct CubeLosses {
  std::vector<LossCount> by_condition;   // in the protocol's order
  std::vector<LossCount> by_repetition;  // 1, 2, ... up to the highest run
};

CubeLosses cube_losses(store::StudyStore& store, const Protocol& protocol);

// {"by_condition": [{"label", "trials", "dropped", "grasped_again"}], "by_repetition": [...]}.
void write_cube_losses(util::JsonWriter& json, const CubeLosses& losses);

}  // namespace handlab::studies
