#include "core/mesh/tetrahedralize.h"

#include <tetgen.h>

#include <cstdio>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace handlab::mesh {

std::string tetgen_switches(const TetrahedralizeOptions& options) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "p"
    << "q" << options.max_radius_edge << "/" << options.min_dihedral_deg;
  if (options.max_volume > 0.0) s << "a" << options.max_volume;
  if (options.keep_boundary) s << "Y";
  return s.str();
}

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options) {
  if (surface.vertices.size() < 4 || surface.triangles.size() < 4)
    throw std::runtime_error("tetrahedralize: the surface has fewer than four triangles");

  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = int(surface.vertices.size());
  in.pointlist = new REAL[surface.vertices.size() * 3];
  for (std::size_t i = 0; i < surface.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * i + std::size_t(k)] = surface.vertices[i][k];
  in.numberoffacets = int(surface.triangles.size());
  in.facetlist = new tetgenio::facet[surface.triangles.size()];
  in.facetmarkerlist = new int[surface.triangles.size()];
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k)
      facet.polygonlist[0].vertexlist[k] = surface.triangles[f][std::size_t(k)];
    in.facetmarkerlist[f] = 1;
  }

  // Q: quiet. TetGen reports errors by throwing an int code.
  std::string switches = tetgen_switches(options) + "Q";
  std::vector<char> buffer(switches.begin(), switches.end());
  buffer.push_back('\0');
  // One TetGen run at a time: its exact predicates keep their error bounds and splitter in
  // globals that every run recomputes (exactinit), so a run on another thread reads passing
  // values and decides orientations differently: another mesh (a study's two jobs each build a
  // soft hand at its start), or a failed assertion (tests/core/tetrahedralize_test.cpp).
  static std::mutex tetgen;
  const std::lock_guard lock(tetgen);
  try {
    ::tetrahedralize(buffer.data(), &in, &out);
  } catch (int code) {
    throw std::runtime_error("TetGen failed with code " + std::to_string(code) +
                             " (1 out of memory, 2 internal error, 3 self-intersecting surface, "
                             "4 tiny feature, 5 close facets, 10 bad input)");
  }
  if (out.numberoftetrahedra <= 0)
    throw std::runtime_error("TetGen produced no tetrahedra: is the surface closed?");

  TetMesh mesh;
  mesh.nodes.resize(std::size_t(out.numberofpoints));
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    mesh.nodes[i] =
        Eigen::Vector3d(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
  // TetGen's node order already has positive orientation, the one the simulator uses;
  // nothing is reordered, so an inverted tet would show as a negative volume.
  mesh.tets.resize(std::size_t(out.numberoftetrahedra));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    auto& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k) tet[std::size_t(k)] = out.tetrahedronlist[4 * t + std::size_t(k)];
  }
  return mesh;
}

}  // namespace handlab::mesh
