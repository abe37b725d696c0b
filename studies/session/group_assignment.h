// The group a participant joins at enrolment: the level of each of the protocol's
// between-participants factors. Factors assigned in order of enrolment are crossed and
// balanced in runs: each run of k enrolments (k the number of their level combinations)
// holds every combination once, in an order drawn from the protocol's seed and the run, so
// that the next assignment cannot be foreseen. Factors assigned from a participant field take
// the level whose values or range hold it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

// (factor, level) in the protocol's order. Throws std::invalid_argument naming the field
// when the participant's value is in no level of a factor it decides.
std::vector<std::pair<std::string, std::string>> assign_groups(
    const Protocol& protocol, const store::Participant& participant, int enrolment);

// The level of a factor assigned from a participant field; throws std::invalid_argument
// saying which value is in no level.
const std::string& level_from_field(const BetweenFactor& factor,
                                    const store::Participant& participant);

}  // namespace handlab::studies
