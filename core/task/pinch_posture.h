// The posture a scripted pinch is placed in. The pads' inverse kinematics from the script's
// hand (palm down, rolled 60°, its wrist's turn fixed) has exactly as many unknowns as the pads'
// goals ask for, and leaves the thumb and index where those goals put them: at their joints'
// limits on both cubes, with the light cube pinned under the index's knuckles. A person
// turns the wrist to pinch with the fingers' joints well inside their ranges: the functional
// posture does that, the same pads on the same goals.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"
#include "core/retarget/fingertip_solver.h"

namespace handlab::sim {

enum class PinchPosture {
  kSolved,      // the pads' inverse kinematics, the wrist's turn fixed
  kFunctional,  // the wrist free, the thumb and index drawn towards FunctionalPosture
};

// "solved" or "functional"; parse_pinch_posture throws std::invalid_argument for another name.
const char* pinch_posture_name(PinchPosture posture);
PinchPosture parse_pinch_posture(const std::string& name);

// The thumb's and index's joint angles a pinch is drawn towards, each with its source, and the
// draw's weight: a radian off the posture weighs as much as `weight` metres of a pad off its goal.
struct PostureAngle {
  std::string dof;     // the skeleton's DOF name
  double angle = 0.0;  // rad
  std::string source;
};
struct FunctionalPosture {
  std::vector<PostureAngle> angles;
  double weight = 0.0;  // m/rad
};
const FunctionalPosture& functional_posture();

// A least squares' pull towards a posture: each of `dofs` drawn towards `anchor`'s angle with
// `weight` (m/rad). Without DOFs it pulls nothing.
struct PosturePull {
  Eigen::VectorXd anchor;
  std::vector<int> dofs;
  double weight = 0.0;  // m/rad
};

// Levenberg-Marquardt from `start`: the features' markers on `goals` (in the features' order
// and weights), the posture drawn by `pull`. With `free_wrist` the posture is first set to the
// pull's anchor and turned and moved so that the first two features' axis lies along their goals'
// and their midpoint on their goals'; the wrist then takes part, its turn drawn back towards that
// placement at a fifth of the pull's weight. Without, the wrist stays where `start` has it and
// only the pull's DOFs move. Angles stay within their limits.
hand::HandPose place_in_posture(const hand::Skeleton& skeleton,
                                const std::vector<retarget::Feature>& features,
                                const std::vector<Eigen::Vector3d>& goals,
                                const hand::HandPose& start, const PosturePull& pull,
                                bool free_wrist);

// The functional posture's DOFs of `skeleton` and an anchor: `pose`'s angles with theirs set.
std::vector<int> posture_dofs(const hand::Skeleton& skeleton);
Eigen::VectorXd posture_anchor(const hand::Skeleton& skeleton, const hand::HandPose& pose);

// The functional posture's pull from `pose` (its other angles kept as they are).
PosturePull functional_pull(const hand::Skeleton& skeleton, const hand::HandPose& pose);

}  // namespace handlab::sim
