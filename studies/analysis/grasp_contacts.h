// How each grasp of a logged trial met the cube, from its frame log: at the moment the task
// first saw the cube lifted between thumb and index, which part of each pinching distal
// phalanx was nearest the cube (its tip, its pad or its base), where the pinch was against the
// cube's centre, and what became of that grasp. `handlab-cli grasps` tallies them per cube or
// condition, for real and simulated participants alike (docs/study.md).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/store/study_store.h"
#include "studies/session/trial_replay.h"

namespace handlab::studies {

// The part of a distal phalanx nearest the cube's centre: the point of the bone's axis
// nearest it is the fingertip's end (tip), the joint's (base), or between them (pad).
enum class PhalanxPart { kBase, kPad, kTip };
const char* phalanx_part_name(PhalanxPart part);

// What became of a grasp: the cube was set down in B, came to rest outside B (a drop), was
// caught again before it landed, or the trial ended while it was held or falling.
enum class GraspOutcome { kPlaced, kDropped, kCaughtAgain, kUnfinished };
const char* grasp_outcome_name(GraspOutcome outcome);

struct GraspContact {
  double time = 0.0;  // s since the trial started, the first frame with the cube grasped
  double held = 0.0;  // s until the pinch let it go (to the trial's last frame if never)
  GraspOutcome outcome = GraspOutcome::kUnfinished;
  PhalanxPart thumb = PhalanxPart::kPad, index = PhalanxPart::kPad;
  // m: the midpoint of the two phalanges' nearest points minus the cube's centre, in the
  // cube's frame (y up the cube)
  Eigen::Vector3d pinch_offset = Eigen::Vector3d::Zero();
  double cube_size = 0.0;  // m
};

// Every grasp of the replayed trial, in time order.
std::vector<GraspContact> grasp_contacts(const TrialReplay& replay);

struct TrialGrasps {
  std::string participant, condition;
  int position = 0, attempt = 0;  // 0-based place in the schedule
  double cube_size = 0.0;         // m, the condition's
  std::vector<GraspContact> grasps;
};

// The grasps of every trial with a result (completed or timed out, practice included) whose
// attempt logged frames, participants in enrolment order (those of `participant` alone when it
// is not empty); trials run without frames are left out.
std::vector<TrialGrasps> study_grasp_contacts(store::StudyStore& store,
                                              const std::string& participant = "");

}  // namespace handlab::studies
