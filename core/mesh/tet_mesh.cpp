#include "core/mesh/tet_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

namespace handlab::mesh {
namespace {

double circumradius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  // Centre x solves 2(p_i - a)·x = |p_i|^2 - |a|^2 for p_i in {b, c, d}.
  Eigen::Matrix3d m;
  m.row(0) = 2.0 * (b - a).transpose();
  m.row(1) = 2.0 * (c - a).transpose();
  m.row(2) = 2.0 * (d - a).transpose();
  const Eigen::Vector3d rhs(b.squaredNorm() - a.squaredNorm(), c.squaredNorm() - a.squaredNorm(),
                            d.squaredNorm() - a.squaredNorm());
  return (m.partialPivLu().solve(rhs) - a).norm();
}

}  // namespace

double signed_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

TetQuality tet_quality(const TetMesh& mesh) {
  TetQuality q;
  q.tets = int(mesh.tets.size());
  q.min_volume = std::numeric_limits<double>::infinity();
  q.min_dihedral_deg = 180.0;
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& tet : mesh.tets) {
    std::array<Eigen::Vector3d, 4> p;
    for (int k = 0; k < 4; ++k) p[std::size_t(k)] = mesh.nodes[std::size_t(tet[std::size_t(k)])];
    const double volume = signed_volume(p[0], p[1], p[2], p[3]);
    q.min_volume = std::min(q.min_volume, volume);
    q.total_volume += volume;
    double shortest = std::numeric_limits<double>::infinity();
    for (const auto& e : kEdges)
      shortest = std::min(shortest, (p[std::size_t(e[0])] - p[std::size_t(e[1])]).norm());
    q.max_radius_edge_ratio =
        std::max(q.max_radius_edge_ratio, circumradius(p[0], p[1], p[2], p[3]) / shortest);
    // Dihedral angle at edge (i, j): between the faces (i, j, k) and (i, j, l).
    for (const auto& e : kEdges) {
      int others[2], n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != e[0] && k != e[1]) others[n++] = k;
      const Eigen::Vector3d& a = p[std::size_t(e[0])];
      const Eigen::Vector3d axis = (p[std::size_t(e[1])] - a).normalized();
      Eigen::Vector3d u = p[std::size_t(others[0])] - a;
      Eigen::Vector3d v = p[std::size_t(others[1])] - a;
      u -= axis * axis.dot(u);
      v -= axis * axis.dot(v);
      const double cosine = std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0);
      q.min_dihedral_deg =
          std::min(q.min_dihedral_deg, std::acos(cosine) * 180.0 / std::numbers::pi);
    }
  }
  if (mesh.tets.empty()) q.min_volume = 0.0;
  return q;
}

}  // namespace handlab::mesh
