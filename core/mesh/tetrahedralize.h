// Quality tetrahedralisation of a closed surface with TetGen.
#pragma once

#include <string>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/tet_mesh.h"

namespace handlab::mesh {

struct TetrahedralizeOptions {
  double max_radius_edge = 1.6;    // -q: radius-edge ratio bound
  double min_dihedral_deg = 12.0;  // -q/: minimum dihedral angle
  double max_volume = 0.0;         // -a: volume bound in m^3; 0 for none
  bool keep_boundary = true;       // -Y: never split the input surface
};

// Throws std::runtime_error when TetGen fails or yields no tets (an open surface does that
// with a zero exit status, so the output is checked, not the status).
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options = {});

// The TetGen switches the options map to (without the quiet flag), for logs and docs.
std::string tetgen_switches(const TetrahedralizeOptions& options);

}  // namespace handlab::mesh
