// The simulated hand's skin: a closed, manifold surface made procedurally from the skeleton
// and shape parameters (a coarse quad cage around the rest pose, smoothed by Catmull-Clark
// subdivision), with linear-blend skinning weights for drawing posed hands.
#pragma once

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/mesh/poly_mesh.h"
#include "core/mesh/surface_mesh.h"

namespace handlab::hand {

struct HandSkin {
  mesh::PolyMesh cage;         // the control mesh (rest pose), attributes = bone weights
  mesh::SurfaceMesh surface;   // triangles after `subdivisions` Catmull-Clark levels
  Eigen::MatrixXd weights;     // surface vertices x bones, rows sum to 1
  double measured_length = 0;  // wrist crease (y = 0) to the farthest skin point along +y
};

// subdivisions: 1 gives the study's flesh resolution; each level quadruples the faces.
HandSkin build_skin(const Skeleton& skeleton, const HandShape& shape, int subdivisions = 1);

// Skin vertex positions for a pose by linear blend skinning (for drawing; the simulator
// moves the flesh itself).
std::vector<Eigen::Vector3d> skin_vertices(const Skeleton& skeleton, const HandSkin& skin,
                                           const HandPose& pose);

}  // namespace handlab::hand
