// A protocol and the study database it is stored in: the protocol a database was created with,
// the study definition a protocol gives a new database, and a participant's planned rows.
// Everything that analyses or exports a finished study needs of its protocol, without the
// session runner, the trial driver or the retargeting they pull in.
#pragma once

#include <string>
#include <vector>

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

// The protocol a study database was created with, parsed from its stored text.
Protocol stored_protocol(store::StudyStore& store);

// A study definition for the database from a protocol.
store::StudyDefinition study_definition(const Protocol& protocol);

// The planned schedule rows of a participant.
std::vector<store::PlannedTrialRow> planned_rows(const Protocol& protocol,
                                                 const std::string& participant, int enrolment);

}  // namespace handlab::studies
