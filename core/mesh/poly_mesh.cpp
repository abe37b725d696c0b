#include "core/mesh/poly_mesh.h"

#include <map>
#include <queue>
#include <utility>

namespace handlab::mesh {
namespace {

using Edge = std::pair<int, int>;
Edge key(int a, int b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

}  // namespace

PolyMesh catmull_clark(const PolyMesh& mesh) {
  const int nv = int(mesh.vertices.size());
  const Eigen::Index na = mesh.attributes.cols();
  const bool has_attributes = mesh.attributes.rows() == nv && na > 0;
  // Work on [position | attributes] rows together.
  Eigen::MatrixXd data(nv, 3 + na);
  for (int v = 0; v < nv; ++v) {
    data.row(v).head<3>() = mesh.vertices[std::size_t(v)].transpose();
    if (has_attributes) data.row(v).tail(na) = mesh.attributes.row(v);
  }
  const Eigen::Index width = data.cols();

  // Face points.
  const int nf = int(mesh.faces.size());
  Eigen::MatrixXd face_point = Eigen::MatrixXd::Zero(nf, width);
  for (int f = 0; f < nf; ++f) {
    for (int v : mesh.faces[std::size_t(f)]) face_point.row(f) += data.row(v);
    face_point.row(f) /= double(mesh.faces[std::size_t(f)].size());
  }
  // Edges and their adjacent faces.
  std::map<Edge, std::vector<int>> edge_faces;
  for (int f = 0; f < nf; ++f) {
    const auto& face = mesh.faces[std::size_t(f)];
    for (std::size_t i = 0; i < face.size(); ++i)
      edge_faces[key(face[i], face[(i + 1) % face.size()])].push_back(f);
  }
  std::map<Edge, int> edge_index;
  Eigen::MatrixXd edge_point(Eigen::Index(edge_faces.size()), width);
  {
    int e = 0;
    for (const auto& [edge, faces] : edge_faces) {
      Eigen::RowVectorXd p = data.row(edge.first) + data.row(edge.second);
      for (int f : faces) p += face_point.row(f);
      edge_point.row(e) = p / double(2 + faces.size());
      edge_index[edge] = e++;
    }
  }
  // Moved original vertices: (F + 2R + (n - 3) P) / n.
  std::vector<std::vector<int>> vertex_faces(static_cast<std::size_t>(nv));
  std::vector<std::vector<int>> vertex_neighbours(static_cast<std::size_t>(nv));
  for (int f = 0; f < nf; ++f)
    for (int v : mesh.faces[std::size_t(f)]) vertex_faces[std::size_t(v)].push_back(f);
  for (const auto& [edge, faces] : edge_faces) {
    vertex_neighbours[std::size_t(edge.first)].push_back(edge.second);
    vertex_neighbours[std::size_t(edge.second)].push_back(edge.first);
  }
  Eigen::MatrixXd moved(nv, width);
  for (int v = 0; v < nv; ++v) {
    const double n = double(vertex_neighbours[std::size_t(v)].size());
    Eigen::RowVectorXd f = Eigen::RowVectorXd::Zero(width), r = Eigen::RowVectorXd::Zero(width);
    for (int face : vertex_faces[std::size_t(v)]) f += face_point.row(face);
    f /= double(vertex_faces[std::size_t(v)].size());
    for (int u : vertex_neighbours[std::size_t(v)]) r += 0.5 * (data.row(v) + data.row(u));
    r /= n;
    moved.row(v) = (f + 2.0 * r + (n - 3.0) * data.row(v)) / n;
  }

  PolyMesh out;
  const int edge_base = nv, face_base = nv + int(edge_faces.size());
  const int total = face_base + nf;
  Eigen::MatrixXd all(total, width);
  all.topRows(nv) = moved;
  all.middleRows(edge_base, Eigen::Index(edge_faces.size())) = edge_point;
  all.bottomRows(nf) = face_point;
  out.vertices.resize(std::size_t(total));
  for (int v = 0; v < total; ++v) out.vertices[std::size_t(v)] = all.row(v).head<3>().transpose();
  if (has_attributes) out.attributes = all.rightCols(na);
  for (int f = 0; f < nf; ++f) {
    const auto& face = mesh.faces[std::size_t(f)];
    const std::size_t k = face.size();
    for (std::size_t i = 0; i < k; ++i) {
      const int prev = face[(i + k - 1) % k], here = face[i], next = face[(i + 1) % k];
      out.faces.push_back({here, edge_base + edge_index[key(here, next)], face_base + f,
                           edge_base + edge_index[key(prev, here)]});
    }
  }
  return out;
}

bool orient_outward(PolyMesh& mesh) {
  // Directed edge -> face; an edge used twice in the same direction means a flip is due.
  std::map<Edge, std::vector<int>> edge_faces;
  for (int f = 0; f < int(mesh.faces.size()); ++f) {
    const auto& face = mesh.faces[std::size_t(f)];
    for (std::size_t i = 0; i < face.size(); ++i)
      edge_faces[key(face[i], face[(i + 1) % face.size()])].push_back(f);
  }
  for (const auto& [edge, faces] : edge_faces)
    if (faces.size() != 2) return false;
  auto has_directed = [&](int f, int a, int b) {
    const auto& face = mesh.faces[std::size_t(f)];
    for (std::size_t i = 0; i < face.size(); ++i)
      if (face[i] == a && face[(i + 1) % face.size()] == b) return true;
    return false;
  };
  std::vector<int> state(mesh.faces.size(), 0);  // 0 unvisited, 1 done
  for (std::size_t seed = 0; seed < mesh.faces.size(); ++seed) {
    if (state[seed]) continue;
    state[seed] = 1;
    std::queue<int> queue;
    queue.push(int(seed));
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      const auto face = mesh.faces[std::size_t(f)];
      for (std::size_t i = 0; i < face.size(); ++i) {
        const int a = face[i], b = face[(i + 1) % face.size()];
        for (int g : edge_faces[key(a, b)]) {
          if (g == f) continue;
          const bool agrees = has_directed(g, b, a);
          if (state[std::size_t(g)]) {
            if (!agrees) return false;
            continue;
          }
          if (!agrees)
            std::reverse(mesh.faces[std::size_t(g)].begin(), mesh.faces[std::size_t(g)].end());
          state[std::size_t(g)] = 1;
          queue.push(g);
        }
      }
    }
  }
  if (enclosed_volume(triangulate(mesh)) < 0)
    for (auto& face : mesh.faces) std::reverse(face.begin(), face.end());
  return true;
}

SurfaceMesh triangulate(const PolyMesh& mesh) {
  SurfaceMesh out;
  out.vertices = mesh.vertices;
  for (const auto& face : mesh.faces) {
    if (face.size() == 3) {
      out.triangles.push_back({face[0], face[1], face[2]});
    } else if (face.size() == 4) {
      const auto& p = mesh.vertices;
      const double d02 = (p[std::size_t(face[0])] - p[std::size_t(face[2])]).squaredNorm();
      const double d13 = (p[std::size_t(face[1])] - p[std::size_t(face[3])]).squaredNorm();
      if (d02 <= d13) {
        out.triangles.push_back({face[0], face[1], face[2]});
        out.triangles.push_back({face[0], face[2], face[3]});
      } else {
        out.triangles.push_back({face[0], face[1], face[3]});
        out.triangles.push_back({face[1], face[2], face[3]});
      }
    } else {
      for (std::size_t i = 1; i + 1 < face.size(); ++i)
        out.triangles.push_back({face[0], face[i], face[i + 1]});
    }
  }
  return out;
}

}  // namespace handlab::mesh
