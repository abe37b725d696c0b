#include "core/mesh/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Geometry>

namespace handlab::mesh {
namespace {

// Does segment pq cross triangle abc (Moller-Trumbore, strictly inside the segment)?
bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (std::abs(det) <= 1e-12 * scale) return false;  // parallel (coplanar contact is not tested)
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(qv) * inv;
  return t > 0.0 && t < 1.0;
}

bool triangles_cross(const SurfaceMesh& m, int i, int j) {
  const auto& ti = m.triangles[std::size_t(i)];
  const auto& tj = m.triangles[std::size_t(j)];
  auto P = [&](int v) -> const Eigen::Vector3d& { return m.vertices[std::size_t(v)]; };
  for (int k = 0; k < 3; ++k) {
    if (segment_hits_triangle(P(ti[std::size_t(k)]), P(ti[std::size_t((k + 1) % 3)]), P(tj[0]),
                              P(tj[1]), P(tj[2])))
      return true;
    if (segment_hits_triangle(P(tj[std::size_t(k)]), P(tj[std::size_t((k + 1) % 3)]), P(ti[0]),
                              P(ti[1]), P(ti[2])))
      return true;
  }
  return false;
}

}  // namespace

std::vector<std::pair<int, int>> self_intersections(const SurfaceMesh& mesh,
                                                    std::size_t max_pairs) {
  const std::size_t n = mesh.triangles.size();
  std::vector<Eigen::AlignedBox3d> boxes(n);
  double mean_size = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    for (int v : mesh.triangles[t]) boxes[t].extend(mesh.vertices[std::size_t(v)]);
    mean_size += boxes[t].sizes().maxCoeff();
  }
  const double cell = 2.0 * mean_size / double(std::max<std::size_t>(n, 1)) + 1e-12;
  auto cell_key = [&](long x, long y, long z) {
    return (x * 73856093L) ^ (y * 19349663L) ^ (z * 83492791L);
  };
  std::unordered_map<long, std::vector<int>> grid;
  for (std::size_t t = 0; t < n; ++t) {
    const Eigen::Vector3d lo = boxes[t].min() / cell, hi = boxes[t].max() / cell;
    for (long x = long(std::floor(lo.x())); x <= long(std::floor(hi.x())); ++x)
      for (long y = long(std::floor(lo.y())); y <= long(std::floor(hi.y())); ++y)
        for (long z = long(std::floor(lo.z())); z <= long(std::floor(hi.z())); ++z)
          grid[cell_key(x, y, z)].push_back(int(t));
  }
  std::vector<std::pair<int, int>> found;
  std::vector<std::pair<int, int>> candidates;
  for (const auto& [key, triangles] : grid)
    for (std::size_t a = 0; a < triangles.size(); ++a)
      for (std::size_t b = a + 1; b < triangles.size(); ++b) {
        const int i = std::min(triangles[a], triangles[b]),
                  j = std::max(triangles[a], triangles[b]);
        if (!boxes[std::size_t(i)].intersects(boxes[std::size_t(j)])) continue;
        const auto& ti = mesh.triangles[std::size_t(i)];
        const auto& tj = mesh.triangles[std::size_t(j)];
        bool shared = false;
        for (int u : ti)
          for (int v : tj) shared |= u == v;
        if (!shared) candidates.emplace_back(i, j);
      }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (const auto& [i, j] : candidates) {
    if (triangles_cross(mesh, i, j)) found.emplace_back(i, j);
    if (found.size() >= max_pairs) break;
  }
  return found;
}

}  // namespace handlab::mesh
