// The study database's schema (internal to core/store): the file's application id, the
// migrations from each schema version to the next, and the checks a file passes before it is
// opened as a study.
#pragma once

#include <cstdint>
#include <string>

#include "core/store/sqlite_database.h"
#include "core/store/study_store.h"

namespace handlab::store {

inline constexpr std::int64_t kApplicationId = 0x484C4142;  // "HLAB"

std::int64_t pragma_int(Database& db, const char* pragma);
// Inspects the file through a connection that sets nothing before anything may write to it;
// its schema version. Throws StoreError saying what the file is when it is not a study this
// build reads.
std::int64_t checked_study_file(const std::string& path);
// Throws StoreError saying what the file is when `path` names a study written under an
// unfinished name (OUT.partial of a merge, PATH.creating of a new study) that was stopped.
void refuse_unfinished_file(const std::string& path);
// Runs the migrations from schema `from` to `to` and records `to`.
void apply_migrations(Database& db, int from, int to);
// A trial's status as the trial table stores it; throws StoreError on another word.
TrialStatus parse_status(const std::string& s);

}  // namespace handlab::store
