#include "core/mesh/surface_mesh.h"

#include <cmath>
#include <map>
#include <utility>

#include <Eigen/Geometry>

namespace handlab::mesh {

SurfaceMesh make_icosphere(double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  SurfaceMesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& v : m.vertices) v.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      m.vertices.push_back((m.vertices[std::size_t(a)] + m.vertices[std::size_t(b)]).normalized());
      const int index = int(m.vertices.size()) - 1;
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(m.triangles.size() * 4);
    for (const auto& [a, b, c] : m.triangles) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  for (auto& v : m.vertices) v *= radius;
  return m;
}

SurfaceTopology surface_topology(const SurfaceMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;  // directed edge -> uses
  for (const auto& tri : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]}];
  std::map<std::pair<int, int>, int> undirected;
  bool oriented = true;
  for (const auto& [edge, uses] : directed) {
    undirected[std::minmax(edge.first, edge.second)] += uses;
    if (uses != 1 || directed.count({edge.second, edge.first}) == 0) oriented = false;
  }
  SurfaceTopology topology;
  topology.every_edge_shared_by_two = !undirected.empty();
  for (const auto& [edge, uses] : undirected)
    if (uses != 2) topology.every_edge_shared_by_two = false;
  topology.consistently_oriented = oriented;
  topology.euler_characteristic =
      int(mesh.vertices.size()) - int(undirected.size()) + int(mesh.triangles.size());
  return topology;
}

double enclosed_volume(const SurfaceMesh& mesh) {
  double volume = 0.0;
  for (const auto& [a, b, c] : mesh.triangles)
    volume += mesh.vertices[std::size_t(a)].dot(
        mesh.vertices[std::size_t(b)].cross(mesh.vertices[std::size_t(c)]));
  return volume / 6.0;
}

}  // namespace handlab::mesh
