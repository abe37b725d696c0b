// Triangle meshes as the renderer draws them: positions, per-vertex normals, indices.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace handlab::render {

struct RenderMesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
};

// An axis-aligned box centred at the origin with the given full extents; flat-shaded faces.
RenderMesh make_box_mesh(const Eigen::Vector3f& extents);
// A square in the xz plane centred at the origin, facing +y.
RenderMesh make_quad_mesh(float size_x, float size_z);
// A unit square in the xy plane centred at the origin, facing +z (a picture's panel).
RenderMesh make_panel_mesh();
// A flat square frame (outline) in the xz plane facing +y: outer size and line width.
RenderMesh make_square_frame_mesh(float outer_size, float line_width);

// A capsule along +y from (0, 0, 0) to (0, length, 0) with the given radius.
RenderMesh make_capsule_mesh(float radius, float length, int segments = 16);
// A triangle mesh with smooth vertex normals (area-weighted face normals).
RenderMesh make_smooth_mesh(const std::vector<Eigen::Vector3f>& positions,
                            const std::vector<std::array<int, 3>>& triangles);

}  // namespace handlab::render
