// The simulated hand's flesh: a tetrahedral mesh of the skin made by TetGen, the coupling
// points that tie it to the bones (after Verschoor, Lobo & Otaduy 2018: for each bone a
// capsule; for every tet the capsule's surface cuts, one point with its barycentric weights
// and the area of capsule surface inside the tet), and a finer render surface embedded in
// the tets so that what is drawn follows the flesh.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/hand/skin.h"
#include "core/mesh/tet_mesh.h"

namespace handlab::hand {

struct Capsule {
  int bone;
  Eigen::Vector3d a, b;  // segment ends in the bone's frame
  double radius;
};

struct CouplingPoint {
  int bone;
  int tet;
  Eigen::Vector4d barycentric;  // of the point in its tet (rest pose)
  Eigen::Vector3d local;        // the point in the bone's frame (rest pose)
  double area;                  // capsule surface area the point stands for (m^2)
};

struct EmbeddedSurface {
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> tet;                      // per vertex
  std::vector<Eigen::Vector4d> barycentric;  // per vertex (may extrapolate slightly)
};

struct FleshOptions {
  // 1: the study's resolution (about 2,300-2,700 tets); 4 and 16: meshes about that many
  // times larger, for scaling measurements.
  int resolution = 1;
  double capsule_sample_spacing = 0.0015;  // m between samples of the capsule surfaces
};

struct HandFlesh {
  mesh::TetMesh tets;
  mesh::TetQuality quality;
  std::vector<Capsule> capsules;
  std::vector<CouplingPoint> coupling;
  EmbeddedSurface render;
  HandSkin skin;  // the surface that was tetrahedralised
};

// Capsules of the bones: one per finger bone, one per metacarpal in the palm.
std::vector<Capsule> bone_capsules(const Skeleton& skeleton, const HandShape& shape);

HandFlesh build_flesh(const Skeleton& skeleton, const HandShape& shape,
                      const FleshOptions& options = {});

// Positions of embedded points for given tet node positions.
std::vector<Eigen::Vector3d> embedded_positions(const EmbeddedSurface& surface,
                                                const mesh::TetMesh& tets,
                                                const std::vector<Eigen::Vector3d>& nodes);

}  // namespace handlab::hand
