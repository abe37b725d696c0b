#include "core/render/render_mesh.h"

#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace handlab::render {
namespace {

void add_quad(RenderMesh& mesh, const std::array<Eigen::Vector3f, 4>& corners,
              const Eigen::Vector3f& normal) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (const auto& c : corners) {
    mesh.positions.push_back(c);
    mesh.normals.push_back(normal);
  }
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

}  // namespace

RenderMesh make_box_mesh(const Eigen::Vector3f& extents) {
  RenderMesh mesh;
  const Eigen::Vector3f h = 0.5f * extents;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3;
      const int v = (axis + 2) % 3;
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = sign;
      std::array<Eigen::Vector3f, 4> corners;
      const float su[4] = {-1, 1, 1, -1};
      const float sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector3f p;
        p[axis] = sign * h[axis];
        p[u] = su[k] * h[u];
        p[v] = sign * sv[k] * h[v];  // flip winding on the negative face
        corners[static_cast<std::size_t>(k)] = p;
      }
      add_quad(mesh, corners, n);
    }
  }
  return mesh;
}

RenderMesh make_quad_mesh(float size_x, float size_z) {
  RenderMesh mesh;
  const float x = 0.5f * size_x;
  const float z = 0.5f * size_z;
  add_quad(mesh,
           {Eigen::Vector3f(-x, 0, z), Eigen::Vector3f(x, 0, z), Eigen::Vector3f(x, 0, -z),
            Eigen::Vector3f(-x, 0, -z)},
           Eigen::Vector3f::UnitY());
  return mesh;
}

RenderMesh make_panel_mesh() {
  RenderMesh mesh;
  add_quad(mesh,
           {Eigen::Vector3f(-0.5f, -0.5f, 0), Eigen::Vector3f(0.5f, -0.5f, 0),
            Eigen::Vector3f(0.5f, 0.5f, 0), Eigen::Vector3f(-0.5f, 0.5f, 0)},
           Eigen::Vector3f::UnitZ());
  return mesh;
}

RenderMesh make_square_frame_mesh(float outer_size, float line_width) {
  RenderMesh mesh;
  const float o = 0.5f * outer_size;
  const float i = o - line_width;
  const Eigen::Vector3f up = Eigen::Vector3f::UnitY();
  // Four strips, each a quad counter-clockwise seen from +y.
  add_quad(mesh,
           {Eigen::Vector3f(-o, 0, o), Eigen::Vector3f(o, 0, o), Eigen::Vector3f(o, 0, i),
            Eigen::Vector3f(-o, 0, i)},
           up);
  add_quad(mesh,
           {Eigen::Vector3f(-o, 0, -i), Eigen::Vector3f(o, 0, -i), Eigen::Vector3f(o, 0, -o),
            Eigen::Vector3f(-o, 0, -o)},
           up);
  add_quad(mesh,
           {Eigen::Vector3f(-o, 0, i), Eigen::Vector3f(-i, 0, i), Eigen::Vector3f(-i, 0, -i),
            Eigen::Vector3f(-o, 0, -i)},
           up);
  add_quad(mesh,
           {Eigen::Vector3f(i, 0, i), Eigen::Vector3f(o, 0, i), Eigen::Vector3f(o, 0, -i),
            Eigen::Vector3f(i, 0, -i)},
           up);
  return mesh;
}

RenderMesh make_capsule_mesh(float radius, float length, int segments) {
  RenderMesh mesh;
  const int rings = segments / 2;  // per hemisphere
  // Rows of vertices from the bottom pole to the top pole; the equator row is doubled so
  // the cylinder part stretches between the hemispheres.
  for (int half = 0; half < 2; ++half) {
    for (int i = 0; i <= rings; ++i) {
      const float phi =
          float(M_PI) * 0.5f * float(half == 0 ? i : rings + i) / float(rings) - float(M_PI) * 0.5f;
      const float y = std::sin(phi), r = std::cos(phi);
      for (int j = 0; j <= segments; ++j) {
        const float theta = 2.0f * float(M_PI) * float(j) / float(segments);
        const Eigen::Vector3f n(r * std::cos(theta), y, r * std::sin(theta));
        mesh.positions.push_back(radius * n + Eigen::Vector3f(0, half == 0 ? 0.0f : length, 0));
        mesh.normals.push_back(n);
      }
    }
  }
  const int row = segments + 1, rows = 2 * (rings + 1);
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j < segments; ++j) {
      const auto a = std::uint32_t(i * row + j), b = a + 1, c = a + std::uint32_t(row), d = c + 1;
      for (std::uint32_t v : {a, c, b, b, c, d}) mesh.indices.push_back(v);
    }
  return mesh;
}

RenderMesh make_smooth_mesh(const std::vector<Eigen::Vector3f>& positions,
                            const std::vector<std::array<int, 3>>& triangles) {
  RenderMesh mesh;
  mesh.positions = positions;
  mesh.normals.assign(positions.size(), Eigen::Vector3f::Zero());
  for (const auto& t : triangles) {
    const Eigen::Vector3f n =
        (positions[std::size_t(t[1])] - positions[std::size_t(t[0])])
            .cross(positions[std::size_t(t[2])] - positions[std::size_t(t[0])]);
    for (int k : t) mesh.normals[std::size_t(k)] += n;
    for (int k : t) mesh.indices.push_back(std::uint32_t(k));
  }
  for (auto& n : mesh.normals) n.normalize();
  return mesh;
}

}  // namespace handlab::render
