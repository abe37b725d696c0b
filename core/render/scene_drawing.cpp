#include "core/render/scene_drawing.h"

namespace handlab::render {
namespace {

constexpr float kFloorSize = 1.2f;        // m
constexpr float kZoneLift = 0.0005f;      // zone outlines sit just above the floor
constexpr float kZoneLineWidth = 0.008f;  // m

Eigen::Matrix4f translation(const Eigen::Vector3d& t) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 1>(0, 3) = t.cast<float>();
  return m;
}

}  // namespace

DrawList draw_task_scene(const task::SceneLayout& layout, const Eigen::Isometry3d& cube_pose,
                         const ScenePalette& palette) {
  // Static meshes are shared between frames so the renderer uploads them once.
  static const auto floor =
      std::make_shared<const RenderMesh>(make_quad_mesh(kFloorSize, kFloorSize));
  static const auto unit_box = std::make_shared<const RenderMesh>(make_box_mesh({1, 1, 1}));

  DrawList list;
  list.items.push_back({floor, Eigen::Matrix4f::Identity(), palette.floor, Shading::kCheckerFloor});

  const auto zone_frame = std::make_shared<const RenderMesh>(
      make_square_frame_mesh(static_cast<float>(layout.zone_size), kZoneLineWidth));
  const auto zone_fill = std::make_shared<const RenderMesh>(
      make_quad_mesh(static_cast<float>(layout.zone_size), static_cast<float>(layout.zone_size)));
  const Eigen::Vector3d lift(0.0, kZoneLift, 0.0);
  const Eigen::Vector4f dim(0.55f, 0.55f, 0.55f, 1.0f);
  for (const auto& [centre, colour] :
       {std::pair{layout.zone_a, palette.zone_a}, std::pair{layout.zone_b, palette.zone_b}}) {
    // A pale fill with a saturated outline reads as a marked area on the floor.
    const Eigen::Vector4f fill = colour.cwiseProduct(dim) + 0.35f * palette.floor;
    list.items.push_back({zone_fill, translation(centre + 0.5 * lift),
                          Eigen::Vector4f(fill.x(), fill.y(), fill.z(), 1.0f), Shading::kLit});
    list.items.push_back({zone_frame, translation(centre + lift), colour, Shading::kLit});
  }

  Eigen::Matrix4f cube = (cube_pose.matrix()).cast<float>();
  cube.block<3, 3>(0, 0) *= static_cast<float>(layout.cube_size);
  list.items.push_back({unit_box, cube, palette.cube, Shading::kLit});
  return list;
}

}  // namespace handlab::render
