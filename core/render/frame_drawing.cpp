#include "core/render/frame_drawing.h"

#include "core/render/scene_drawing.h"
#include "core/render/sim_drawing.h"

namespace handlab::render {

namespace {

DrawList draw_scene_of(const task::SceneLayout& layout, const store::FrameRecord& frame) {
  Eigen::Isometry3d cube = Eigen::Isometry3d::Identity();
  cube.linear() = frame.cube_rotation.cast<double>().toRotationMatrix();
  cube.translation() = frame.cube_position.cast<double>();
  return draw_task_scene(layout, cube);
}

}  // namespace

DrawList draw_stored_frame(const task::SceneLayout& layout, const BoneMeshes& hand,
                           const store::FrameRecord& frame) {
  DrawList list = draw_scene_of(layout, frame);
  std::vector<Eigen::Isometry3d> bones(frame.bone_positions.size());
  for (std::size_t b = 0; b < bones.size(); ++b) {
    bones[b] = Eigen::Isometry3d::Identity();
    bones[b].linear() = frame.bone_rotations[b].cast<double>().toRotationMatrix();
    bones[b].translation() = frame.bone_positions[b].cast<double>();
  }
  draw_bone_frames(list, hand, bones, SimDrawStyle{}.skin);
  return list;
}

DrawList draw_soft_hand_frame(const task::SceneLayout& layout, const hand::EmbeddedSurface& skin,
                              const mesh::TetMesh& tets,
                              const std::vector<Eigen::Vector3d>& flesh_nodes,
                              const store::FrameRecord& frame) {
  DrawList list = draw_scene_of(layout, frame);
  draw_skin(list, hand::embedded_positions(skin, tets, flesh_nodes), skin.triangles,
            Eigen::Isometry3d::Identity(), SimDrawStyle{}.skin);
  return list;
}

}  // namespace handlab::render
