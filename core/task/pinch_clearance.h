// The pinch's posture by a rule fixed before any closing ran with it: the pads on their goals
// and no other skin within 2 mm of the cube or of the column under it. The palm-down pinch whose
// fingers stretch along the floor lays the index across a 6 cm cube's top (its middle phalanx's
// target 14 mm inside), and the soft hand then pins the cube to the floor through every bone's
// tracking spring (133-143 N on the top): a grip of three faces that no hand makes on a real cube
// and that the grasp map does not mean to measure (docs/simulator.md, the scripted pinch).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/retarget/fingertip_solver.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/rigid_body.h"
#include "core/task/pinch_posture.h"

namespace handlab::sim {

// The rule: both pads within kPadReach of their goals, every other bone's skin at least
// kSkinClearance off the cube and out of the column under it (the hand comes down onto its pinch
// from above: skin placed under the cube, below the floor, passed through the cube on the way;
// the curled ring and little fingers of a functional pitch of 10° under the 6 cm cube pressed its
// top with 497 N). A pinch is placed by it where its other skin lies deeper than kPinningDepth
// inside the cube or that column.
constexpr double kPadReach = 0.001;       // m
constexpr double kSkinClearance = 0.002;  // m
constexpr double kPinningDepth = 0.002;   // m
// A hand the rule places comes down onto its pinch in the open pose with its flesh behind its
// targets by up to about 5 mm (the thumb's base held off by the flesh's strain: the bones'
// largest offset 4.3-4.9 mm before any contact, `sim pinch --trace`), more than the rule's
// clearance: so its open pose is placed with every skin point aimed this far off the cube and
// its column.
constexpr double kDescentClearance = 0.005;  // m

struct SkinClearance {
  // m: the nearest skin of the other bones to the cube (< 0: inside; placement_clearance's also
  // inside the column under it)
  double distance = 0.0;
  int bone = -1;  // whose skin that is
};

// How near a cube of half sides `half` at `cube` the skin of every bone but `pad_bones` comes
// with the hand at `pose` (each surface node carried rigidly by its bone:
// HandSimModel::bone_skin).
SkinClearance skin_clearance(const hand::Skeleton& skeleton, const HandSimModel& model,
                             const hand::HandPose& pose, const RigidPose& cube,
                             const Eigen::Vector3d& half, const std::array<int, 2>& pad_bones);
// As skin_clearance, but a point inside the column under the cube counts as inside the cube, as
// deep as it lies from the column's nearer side: how the pinch's rule measures a placement on
// the floor. A point below the cube's bottom beside the column keeps its distance to the cube.
SkinClearance placement_clearance(const hand::Skeleton& skeleton, const HandSimModel& model,
                                  const hand::HandPose& pose, const RigidPose& cube,
                                  const Eigen::Vector3d& half, const std::array<int, 2>& pad_bones);

struct ClearPinch {
  hand::HandPose pose;
  double pad_error = 0.0;  // m: the farther pad from its goal
  SkinClearance clearance;
  bool meets_rule() const { return pad_error <= kPadReach && clearance.distance >= kSkinClearance; }
};

// A posture found by least squares from `start` (Levenberg-Marquardt over the wrist's pose and
// every joint within its limits) whose `features` (the pads first, as markers of `skeleton`)
// reach `goals` while the other skin keeps kSkinClearance off the cube and out of its column: a
// penalty on the skin nearer than that to either, raised step by step, each step solved from the
// last, the posture drawn by `pull` (the functional posture's: its pads reach their goals with its
// joints off their limits, where the skin's penalty alone bends them to their limits). Where the
// clearance binds, the pads may stop short of their goals: `meets_rule` says whether they reached
// them.
ClearPinch clear_pinch(const hand::Skeleton& skeleton, const HandSimModel& model,
                       const std::vector<retarget::Feature>& features,
                       const std::vector<Eigen::Vector3d>& goals, const RigidPose& cube,
                       const std::array<int, 2>& pad_bones, const hand::HandPose& start,
                       const PosturePull& pull = {});

// The open pose a hand placed by the rule comes down in: from `start`, the fingers alone (the
// wrist stays) moved by the same least squares so that `features` reach `goals` (the pads'
// places off the faces) with the penalty on every skin point, the pads' too, nearer than
// kDescentClearance to the cube or its column. Fingers alone barely move the skin by their
// knuckles: the pose can stop short of that clearance.
hand::HandPose clear_descent(const hand::Skeleton& skeleton, const HandSimModel& model,
                             const std::vector<retarget::Feature>& features,
                             const std::vector<Eigen::Vector3d>& goals, const RigidPose& cube,
                             const hand::HandPose& start);

}  // namespace handlab::sim
