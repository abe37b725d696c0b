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

// The zones' meshes for a zone size, shared between frames like the static ones: the
// renderer uploads them once and keeps the ground's picture while nothing on it changes.
struct ZoneMeshes {
  double size = -1;
  std::shared_ptr<const RenderMesh> frame, fill;
};

const ZoneMeshes& zone_meshes(double size) {
  thread_local ZoneMeshes meshes;
  if (meshes.size != size) {
    meshes.size = size;
    meshes.frame = std::make_shared<const RenderMesh>(
        make_square_frame_mesh(static_cast<float>(size), kZoneLineWidth));
    meshes.fill = std::make_shared<const RenderMesh>(
        make_quad_mesh(static_cast<float>(size), static_cast<float>(size)));
  }
  return meshes;
}

DrawItem on_ground(DrawItem item) {
  item.ground = true;
  return item;
}

}  // namespace

DrawList draw_task_scene(const task::SceneLayout& layout, const Eigen::Isometry3d& cube_pose,
                         const ScenePalette& palette) {
  // Static meshes are shared between frames so the renderer uploads them once.
  static const auto floor =
      std::make_shared<const RenderMesh>(make_quad_mesh(kFloorSize, kFloorSize));
  static const auto unit_box = std::make_shared<const RenderMesh>(make_box_mesh({1, 1, 1}));

  DrawList list;
  list.items.push_back(
      on_ground({floor, Eigen::Matrix4f::Identity(), palette.floor, Shading::kCheckerFloor}));

  const ZoneMeshes& zone = zone_meshes(layout.zone_size);
  const Eigen::Vector3d lift(0.0, kZoneLift, 0.0);
  const Eigen::Vector4f dim(0.55f, 0.55f, 0.55f, 1.0f);
  for (const auto& [centre, colour] :
       {std::pair{layout.zone_a, palette.zone_a}, std::pair{layout.zone_b, palette.zone_b}}) {
    // A pale fill with a saturated outline reads as a marked area on the floor.
    const Eigen::Vector4f fill = colour.cwiseProduct(dim) + 0.35f * palette.floor;
    list.items.push_back(
        on_ground({zone.fill, translation(centre + 0.5 * lift),
                   Eigen::Vector4f(fill.x(), fill.y(), fill.z(), 1.0f), Shading::kLit}));
    list.items.push_back(
        on_ground({zone.frame, translation(centre + lift), colour, Shading::kLit}));
  }

  Eigen::Matrix4f cube = (cube_pose.matrix()).cast<float>();
  cube.block<3, 3>(0, 0) *= static_cast<float>(layout.cube_size);
  list.items.push_back({unit_box, cube, palette.cube, Shading::kLit});
  return list;
}

void draw_panel(DrawList& list, const task::SceneLayout& layout,
                std::shared_ptr<const Image> picture) {
  static const auto panel = std::make_shared<const RenderMesh>(make_panel_mesh());
  if (!picture || picture->width <= 0 || picture->height <= 0) return;
  constexpr float kWidth = 0.40f, kBehindZones = 0.25f, kBottom = 0.08f;  // m
  const float height = kWidth * float(picture->height) / float(picture->width);
  const Eigen::Vector3f middle = (0.5 * (layout.zone_a + layout.zone_b)).cast<float>();
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
  model(0, 0) = kWidth;
  model(1, 1) = height;
  model.block<3, 1>(0, 3) =
      Eigen::Vector3f(middle.x(), kBottom + 0.5f * height, middle.z() - kBehindZones);
  DrawItem item{panel, model, Eigen::Vector4f::Ones(), Shading::kPicture};
  item.picture = std::move(picture);
  list.items.push_back(std::move(item));
}

}  // namespace handlab::render
