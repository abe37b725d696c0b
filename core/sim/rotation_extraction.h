// The rotation of a deformation gradient (the R of its polar decomposition F = RS), by the
// warm-started iteration of Müller et al. 2016, "A Robust Method to Extract the Rotational Part
// of Deformations": a few cross products a tet instead of an SVD, robust to inverted tets.
#pragma once

#include <Eigen/Geometry>

namespace handlab::sim {

// Refines `q` (the previous step's rotation, or identity) towards the rotation of `f`. Warm
// started, it converges in one or two iterations; from half a turn away the iteration can
// stall, and then the rotation comes from an SVD of F instead (reflection removed).
void extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations = 20);

}  // namespace handlab::sim
