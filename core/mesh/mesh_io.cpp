#include "core/mesh/mesh_io.h"

#include <iomanip>

#include "core/util/output_file.h"

namespace handlab::mesh {

void write_obj(const SurfaceMesh& mesh, const std::string& path) {
  util::write_output(path, [&](std::ostream& out) {
    out << std::setprecision(9) << "# handlab surface, metres\n";
    for (const auto& v : mesh.vertices)
      out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : mesh.triangles)
      out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  });
}

void write_vtk(const TetMesh& mesh, const std::string& path) {
  util::write_output(path, [&](std::ostream& out) {
    out << std::setprecision(9)
        << "# vtk DataFile Version 3.0\nhandlab tetrahedral flesh (metres)\nASCII\n"
        << "DATASET UNSTRUCTURED_GRID\nPOINTS " << mesh.nodes.size() << " double\n";
    for (const auto& p : mesh.nodes) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "CELLS " << mesh.tets.size() << ' ' << mesh.tets.size() * 5 << '\n';
    for (const auto& t : mesh.tets)
      out << "4 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
    out << "CELL_TYPES " << mesh.tets.size() << '\n';
    for (std::size_t i = 0; i < mesh.tets.size(); ++i) out << "10\n";
  });
}

}  // namespace handlab::mesh
