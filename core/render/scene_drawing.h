// Turns the task scene into draw items: a checkered floor, the two zones and the cube.
#pragma once

#include <memory>

#include <Eigen/Geometry>

#include "core/render/draw_list.h"
#include "core/task/scene_layout.h"

namespace handlab::render {

// Colours of the scene, shared by the app, offscreen pictures and tests.
struct ScenePalette {
  Eigen::Vector4f floor{0.62f, 0.63f, 0.65f, 1.0f};
  Eigen::Vector4f zone_a{0.20f, 0.70f, 0.30f, 1.0f};
  Eigen::Vector4f zone_b{0.20f, 0.45f, 0.90f, 1.0f};
  Eigen::Vector4f cube{0.92f, 0.42f, 0.10f, 1.0f};
};

DrawList draw_task_scene(const task::SceneLayout& layout, const Eigen::Isometry3d& cube_pose,
                         const ScenePalette& palette = {});

// A picture (the instruction, a questionnaire) on an upright panel 40 cm wide standing behind
// the zones and facing the participant, as a headset shows what a window shows beside the
// scene; its height keeps the picture's aspect.
void draw_panel(DrawList& list, const task::SceneLayout& layout,
                std::shared_ptr<const Image> picture);

}  // namespace handlab::render
