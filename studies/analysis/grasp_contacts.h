// How each grasp of a logged trial met the cube, from its frame log: at the moment the task
// first saw the cube lifted between thumb and index, which part of each pinching distal
// phalanx was nearest the cube (its tip, its pad or its base), where the pinch was against the
// cube's centre, and what became of that grasp. `handlab-cli grasps` tallies them per cube or
// condition, for real and simulated participants alike (docs/study.md).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/store/study_store.h"
#include "studies/analysis/logged_closing.h"
#include "studies/session/trial_replay.h"

namespace handlab::studies {

// The part of a distal phalanx nearest the cube's centre: the point of the bone's axis
// nearest it is the fingertip's end (tip), the joint's (base), or between them (pad).
enum class PhalanxPart { kBase, kPad, kTip };
const char* phalanx_part_name(PhalanxPart part);

// What became of a grasp once the pinch let the cube go: it was set down in B (placed), came
// to rest outside B (dropped), came down onto the floor and was grasped again before it rested
// (landed), was grasped again before it touched the floor (caught_again), or the trial ended
// first (unfinished). The task counts a drop only for the second; `landed` is lost all the same.
enum class GraspOutcome { kPlaced, kDropped, kLanded, kCaughtAgain, kUnfinished };
const char* grasp_outcome_name(GraspOutcome outcome);
// Whether the pinch lost the cube: it came down onto the floor out of B.
bool lost(GraspOutcome outcome);

struct GraspContact {
  double time = 0.0;  // s since the trial started, the first frame with the cube grasped
  double held = 0.0;  // s until the pinch let it go (to the trial's last frame if never)
  GraspOutcome outcome = GraspOutcome::kUnfinished;
  PhalanxPart thumb = PhalanxPart::kPad, index = PhalanxPart::kPad;
  // m: the midpoint of the two phalanges' nearest points minus the cube's centre, in the
  // scene's axes (x and z along the floor, y up)
  Eigen::Vector3d pinch_offset = Eigen::Vector3d::Zero();
  double cube_size = 0.0;                // m
  std::optional<LoggedClosing> closing;  // in the grasp map's terms, when read
};

// Every grasp of the replayed trial, in time order; with `closings`, each one's closing read
// by it (a reader of the replay's simulated hand).
std::vector<GraspContact> grasp_contacts(const TrialReplay& replay,
                                         const ClosingReader* closings = nullptr);

struct TrialGrasps {
  std::string participant, condition;
  int position = 0;        // 0-based place in the schedule
  int attempt = 0;         // from 1
  double cube_size = 0.0;  // m, the condition's
  std::vector<GraspContact> grasps;
  // The intermediate hand's jitter over the trial (core/task/tracker_jitter.h, 0.1 s): RMS of
  // the wrist's offsets per axis (m) and of the joint angles' (rad), the grasp map's jitter
  // factor; NaN when fewer than two frames held a hand.
  double jitter_root_rms = std::numeric_limits<double>::quiet_NaN();
  double jitter_angle_rms = std::numeric_limits<double>::quiet_NaN();
};

// The grasps of every trial with a result (completed or timed out, practice included) whose
// attempt logged frames, participants in enrolment order (those of `participant` alone when it
// is not empty), each with its closing; trials run without frames are left out.
std::vector<TrialGrasps> study_grasp_contacts(store::StudyStore& store,
                                              const std::string& participant = "");

}  // namespace handlab::studies
