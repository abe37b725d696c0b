// Tetrahedral meshes and their quality measures.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace handlab::mesh {

struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<std::array<int, 4>> tets;  // positive orientation: (b-a)·((c-a)×(d-a)) > 0
};

double signed_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d);

struct TetQuality {
  int tets = 0;
  double min_volume = 0.0;             // m^3
  double total_volume = 0.0;           // m^3
  double max_radius_edge_ratio = 0.0;  // circumradius / shortest edge; 0.612 for a regular tet
  double min_dihedral_deg = 0.0;       // smallest dihedral angle over all tets
};
TetQuality tet_quality(const TetMesh& mesh);

}  // namespace handlab::mesh
