// One study from several databases of the same protocol (`handlab-cli merge`): the shards of a
// simulated study run apart (simulate --shard, docs/cluster.md), or one study recorded on
// several lab machines. Every participant comes with all that is stored of them: enrolment,
// schedule, sessions, attempts (redone, skipped and aborted ones with their reasons), events,
// frames, questionnaire answers, a simulated person's parameters and memory.
#pragma once

#include <string>
#include <vector>

#include "core/store/study_store.h"

namespace handlab::store {

struct MergeOptions {
  // Write the study though its parts lack participants its plan names; it then says it is
  // partial (StudyStore::completeness) until merged again with the rest.
  bool partial = false;
  // An existing `out` is merged again with the parts and replaced, unless its plan says it is
  // whole already, when it is left as it is. Without it, an existing `out` is refused.
  bool update = false;
};

struct MergeResult {
  int participants = 0;        // in the merged study
  int duplicates = 0;          // participants found in two parts with the same data, taken once
  bool renumbered = false;     // places in the enrolment order clashed: renumbered in part order
  bool whole_already = false;  // update: `out` was whole, nothing was written
  StudyCompleteness completeness;  // of the merged study
};

// Writes the study `out` (which must not exist) from `parts`, each opened read-only and
// never changed. A participant keeps its place in the enrolment order where the parts' places
// are distinct (shards); otherwise participants are placed part by part, each part's in its
// order. `out` appears only when complete: it is written as OUT.partial (a stale one, left by
// a merge that was killed, is replaced) and renamed at the end. Throws StoreError naming the
// file and the reason: `out` exists; a part is missing, not a handlab study, or fails
// SQLite's integrity check; a part's protocol, plan or simulated people's population seed
// differs from the first part's; a
// participant is in two parts with different data; the parts lack planned participants and
// `options.partial` is not set.
MergeResult merge_studies(const std::vector<std::string>& parts, const std::string& out,
                          const MergeOptions& options = {});

}  // namespace handlab::store
