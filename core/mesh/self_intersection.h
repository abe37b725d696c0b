// Pairs of triangles of a surface that cross each other (triangles sharing a vertex are
// neighbours and not tested). A uniform grid keeps it near linear in the triangle count.
#pragma once

#include <utility>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace handlab::mesh {

std::vector<std::pair<int, int>> self_intersections(const SurfaceMesh& mesh,
                                                    std::size_t max_pairs = 100);

}  // namespace handlab::mesh
