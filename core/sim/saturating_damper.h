// A damper whose force saturates, stepped by backward Euler: over a step h that moves a point by
// d, its velocity is v = d / h and its force c v / (1 + |v| / v0), which approaches c v0 and
// never passes it. The step's energy is h psi(v), psi(v) = c v0^2 (u - ln(1 + u)), u = |v| / v0:
// convex, so Newton's matrix stays positive definite (v0 = 0: the linear damper, c |d|^2 / 2h).
#pragma once

#include <Eigen/Core>

#include "core/sim/saturating_spring.h"

namespace handlab::sim {

// The damper c (N s/m or N m s/rad) moved by d over the step h (s), its force saturating past
// the speed v0 (m/s or rad/s; 0: linear): the step's energy, its gradient in d (the damper's
// force) and Hessian.
SpringResponse saturating_damper(double c, double v0, double h, const Eigen::Vector3d& d);

}  // namespace handlab::sim
