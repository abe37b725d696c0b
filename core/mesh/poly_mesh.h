// Polygon meshes (quads mostly) with per-vertex attributes, Catmull-Clark subdivision and
// triangulation: the skin is built as a coarse cage and smoothed this way.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/mesh/surface_mesh.h"

namespace handlab::mesh {

struct PolyMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;
  // Attributes subdivided like positions (e.g. skinning weights): one row per vertex.
  Eigen::MatrixXd attributes;
};

// One level of Catmull-Clark subdivision of a closed manifold mesh (every face becomes
// quads); attributes follow the same rules as positions.
PolyMesh catmull_clark(const PolyMesh& mesh);

// Makes face orientations agree across shared edges (breadth-first) and outward (positive
// enclosed volume). Returns false when the mesh is not orientable or not closed.
bool orient_outward(PolyMesh& mesh);

// Splits each quad along its shorter diagonal.
SurfaceMesh triangulate(const PolyMesh& mesh);

}  // namespace handlab::mesh
