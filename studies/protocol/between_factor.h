// A between-participants factor: each participant is in one of its levels for the whole
// study, assigned at enrolment either in order of enrolment (balanced) or from what the
// participant form records (VR experience, sex and handedness by value; age and hand length
// by range). Read from the protocol's "between" array (docs/study.md).
#pragma once

#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/util/json_value.h"
#include "studies/protocol/protocol_reader.h"

namespace handlab::studies {

enum class GroupAssignment {
  kEnrolment,         // every run of k enrolments holds each of the k groups once, seeded order
  kParticipantField,  // the level whose values (or range) hold the participant's field
};

struct BetweenLevel {
  std::string name;                 // a label for people, as within levels' are
  std::vector<std::string> values;  // text fields: the values that place a person here
  double from = -std::numeric_limits<double>::infinity();  // numeric fields: [from, below)
  double below = std::numeric_limits<double>::infinity();
};

struct BetweenFactor {
  std::string name;
  GroupAssignment assignment = GroupAssignment::kEnrolment;
  std::string field;  // kParticipantField: vr_experience, sex, handedness, age, hand_length
  std::vector<BetweenLevel> levels;
};

// Whether the participant field holds a number (age in years, hand_length in m).
bool numeric_participant_field(const std::string& field);

// How its participants are assigned, in words: "balanced in order of enrolment", or "by "
// and the field as `field_name` names it.
std::string assignment_rule(const BetweenFactor& factor, const std::string& field_name);

// The level a participant field's answer places a person in: the one whose values hold it
// (case and surrounding spaces aside, as the form's answers are typed), or whose range holds
// the number; nullptr when none does.
const BetweenLevel* level_holding(const BetweenFactor& factor, const std::string& answer);
const BetweenLevel* level_holding(const BetweenFactor& factor, double number);

// The protocol's "between" array. `taken` holds the names a factor may not have (the within
// factors' and the exports' columns): a between factor becomes a column beside them.
std::vector<BetweenFactor> read_between_factors(const ProtocolReader& r,
                                                const util::JsonValue& between,
                                                const std::set<std::string>& taken);

}  // namespace handlab::studies
