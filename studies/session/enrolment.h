// Enrolling a participant, as the CLI and the app's form do it: the values checked by the
// store's own rules first, each refusal naming its field, then the schedule drawn from the
// study's seed and the enrolment order. And a protocol in a few lines, for a person to
// check before a study is created from it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"

namespace handlab::studies {

struct FieldProblem {
  std::string field;  // "id", "age", "sex", "handedness", "hand_length", "vr_experience"
  std::string message;
};

// What the store would refuse of these values (its CHECK constraints), a duplicate id among
// `enrolled`, and, with a protocol, a field that puts the participant in no level of a
// between factor it decides. Empty: acceptable.
std::vector<FieldProblem> participant_problems(const store::Participant& participant,
                                               const std::vector<store::Participant>& enrolled,
                                               const Protocol* protocol = nullptr);

// Enrols after the checks (throws std::invalid_argument with the first problem's message),
// in the groups of the protocol's between factors; returns the number of trials planned.
int enrol_participant(store::StudyStore& store, const store::Participant& participant);

// Changes what may change after enrolment (age, sex, handedness, hand length, VR experience,
// notes, and the group a changed field decides); the id and the schedule stay. Throws
// std::invalid_argument on a refused value.
void update_participant(store::StudyStore& store, const store::Participant& participant);

// (label, value) lines: name, title, factors and levels, conditions, blocks,
// counterbalancing, practice, questionnaire items and timing, scene, simulated hand, timeout.
std::vector<std::pair<std::string, std::string>> protocol_summary(const Protocol& protocol);

}  // namespace handlab::studies
