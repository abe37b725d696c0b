#include "core/render/sim_drawing.h"

#include "core/render/hand_drawing.h"
#include "core/render/scene_drawing.h"

namespace handlab::render {

DrawList draw_sim_state(const task::SceneLayout& layout, const hand::HandFlesh& flesh,
                        const sim::HandSimModel& model, const sim::HandSimState& state,
                        const SimDrawStyle& style) {
  Eigen::Isometry3d cube = Eigen::Isometry3d::Identity();
  cube.linear() = state.cube_pose.rotation.toRotationMatrix();
  cube.translation() = state.cube_pose.position;
  DrawList list = draw_task_scene(layout, cube);
  draw_skin(list, hand::embedded_positions(flesh.render, flesh.tets, state.node_position),
            flesh.render.triangles, Eigen::Isometry3d::Identity(), style.skin);
  if (!style.contacts) return list;
  // One sphere mesh for every point and frame: the renderer uploads it once.
  static const auto sphere = std::make_shared<const RenderMesh>(make_capsule_mesh(1.0f, 0.0f, 10));
  auto point = [&](const Eigen::Vector3d& at, const Eigen::Vector4f& color) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<3, 3>(0, 0) *= style.contact_radius;
    m.block<3, 1>(0, 3) = at.cast<float>();
    DrawItem item{sphere, m, color, Shading::kUnlit};
    item.overlay = true;  // inside the flesh or behind the cube, and still shown
    list.items.push_back(item);
  };
  for (const sim::ContactAnchor& c : state.node_cube)
    point(state.node_position[std::size_t(c.point)], style.hand_on_cube);
  for (const sim::ContactAnchor& c : state.sample_cube)
    point(sim::skin_sample_position(model, state, c.point), style.hand_on_cube);
  for (const sim::ContactAnchor& c : state.node_floor)
    point(state.node_position[std::size_t(c.point)], style.hand_on_floor);
  for (const sim::ContactAnchor& c : state.corner_floor)
    point(sim::cube_corner(model, state.cube_pose, c.point), style.cube_on_floor);
  return list;
}

}  // namespace handlab::render
