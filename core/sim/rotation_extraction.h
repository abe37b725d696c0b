// The rotation of a deformation gradient (the R of its polar decomposition F = RS), by the
// warm-started iteration of Müller et al. 2016, "A Robust Method to Extract the Rotational Part
// of Deformations": a few cross products a tet instead of an SVD, robust to inverted tets.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace handlab::sim {

// Refines `q` (the previous step's rotation, or identity) towards the rotation of `f`. Warm
// started, it converges in one or two iterations; from half a turn away the iteration can
// stall, and then the rotation comes from an SVD of F instead (reflection removed).
void extract_rotation(const Eigen::Matrix3d& f, Eigen::Quaterniond& q, int max_iterations = 20);

// Four at once: lane l's F is f[3i + j][l] (row-major), its rotation *q[l] (lanes from `count`
// on are ignored). Two Newton iterations run in the lanes of the vector unit; a lane they do
// not settle (a turn beyond the series' range, F near inversion, not yet converged) is done
// by extract_rotation from where it started. Returns how many lanes (of `count`) settled.
int extract_rotations(const Eigen::Array4d (&f)[9], Eigen::Quaterniond* const (&q)[4], int count);

// The rotation matrices (row-major) of four unit quaternions (w, x, y, z), as Eigen's
// toRotationMatrix.
void rotation_matrices(const Eigen::Array4d& w, const Eigen::Array4d& x, const Eigen::Array4d& y,
                       const Eigen::Array4d& z, Eigen::Array4d (&r)[9]);

}  // namespace handlab::sim
