// Closed triangle surfaces in double precision (skin, test shapes) and their topology checks.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace handlab::mesh {

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// A sphere made by subdividing an icosahedron `subdivisions` times (20·4^s triangles).
SurfaceMesh make_icosphere(double radius, int subdivisions);

struct SurfaceTopology {
  bool every_edge_shared_by_two = false;  // closed and edge-manifold
  bool consistently_oriented = false;     // each edge used once in each direction
  int euler_characteristic = 0;           // V - E + F; 2 for a sphere-like surface
};
SurfaceTopology surface_topology(const SurfaceMesh& mesh);

// Volume enclosed by a closed, outward-oriented surface (divergence theorem).
double enclosed_volume(const SurfaceMesh& mesh);

}  // namespace handlab::mesh
