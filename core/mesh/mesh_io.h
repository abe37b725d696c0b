// Writing meshes: Wavefront OBJ surfaces and legacy ASCII VTK unstructured grids of tets.
#pragma once

#include <string>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/tet_mesh.h"

namespace handlab::mesh {

void write_obj(const SurfaceMesh& mesh, const std::string& path);
void write_vtk(const TetMesh& mesh, const std::string& path);

}  // namespace handlab::mesh
