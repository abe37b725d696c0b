#include "core/render/render_mesh.h"

#include <array>

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

}  // namespace handlab::render
