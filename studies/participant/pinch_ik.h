// The simulated participant's own inverse kinematics: where its joints go for its fingertips
// to be where it wants them. Damped least squares on weighted point goals (Buss 2004,
// "Introduction to inverse kinematics with Jacobian transpose, pseudoinverse and damped least
// squares methods"; Wampler 1986), the joints held inside their limits by projection, the
// wrist free to move (its rotation fixed by the posture). The participant's own code: it
// shares nothing with any retargeting strategy (PinchIkTest.NoRetargetingInTheParticipant).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"

namespace handlab::studies {

struct PointGoal {
  int bone = -1;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();   // the point in the bone's frame
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // where it should be (world, m)
  double weight = 1.0;
};

struct PinchIkOptions {
  double root_weight = 1e-3;       // (m^2/m^2): the wrist's shift from where it starts, penalised
  double damping = 1e-6;           // (m^2): Levenberg-Marquardt damping of every step
  double max_step = 0.3;           // rad (the wrist's shift in translation_unit): longest step
  double translation_unit = 0.05;  // m: the wrist's shift counts in these against max_step
  int iterations = 200;
  double step_tolerance = 1e-9;  // stop when no parameter moves more (rad, m)
};

struct PinchIkResult {
  int iterations = 0;
  double residual = 0.0;  // m: the weighted RMS distance of the points to their targets
};

// Moves `pose` (angles and root position; root rotation kept) towards the goals.
PinchIkResult solve_pinch_ik(const hand::Skeleton& skeleton, hand::HandPose& pose,
                             const std::vector<PointGoal>& goals,
                             const PinchIkOptions& options = {});

}  // namespace handlab::studies
