// A study database's results as long-format CSV for R, JASP or jamovi, and its progress per
// participant. Practice trials stay in the database and out of these tables.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/store/study_store.h"

namespace handlab::studies {

// trials.csv: participant, age, sex, handedness, hand_length, vr_experience, one column per
// between-participants factor (the participant's group), block, order, one column per
// within factor, repetition, completion_time_s, outcome (success | timeout |
// skipped), grasps, drops, attempt. One row per planned trial that has a result; a skipped
// trial's numbers are NA (its row left out with include_skipped false, as an analysis needs).
void write_trials_csv(store::StudyStore& store, std::ostream& out, bool include_skipped = true);
// questionnaire.csv: participant, covariates, groups, block, order, factors, repetition, then one
// column per questionnaire item.
void write_questionnaire_csv(store::StudyStore& store, std::ostream& out);
// frames.csv: the frame log of the same trials (completed or timed out; the attempt that
// gave the result), one row per logged step: participant, covariates, groups, block, order,
// factors, repetition, attempt, outcome, t (s), phase (ready | started | grasped | released | done
// | failed), the cube's centre, the thumb's and index's flesh on the cube (0/1), the simulated
// thumb and index tips (the ends of their distal bones) and their distance, aperture, all in
// metres in the scene frame (floor y = 0), and tracked_aperture, the tracked hand's thumb-index
// tip distance (NA without a hand). Trials run without frames have no rows.
void write_frames_csv(store::StudyStore& store, std::ostream& out);

struct ParticipantStatus {
  std::string id;
  int trials_planned = 0;
  int trials_completed = 0;  // ended, by success or by timeout
  int trials_skipped = 0;
  int trials_aborted = 0;  // attempts interrupted (each is, or was, run again)
  std::optional<store::PlannedTrialRow> next;
  std::string next_condition;
};

std::vector<ParticipantStatus> study_status(store::StudyStore& store);

}  // namespace handlab::studies
