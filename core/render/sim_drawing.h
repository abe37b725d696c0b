// Draws any state of the soft-hand simulator: the task scene with the cube where the state
// has it, the flesh's skin deformed with the nodes and, on request, the contact points
// (flesh on the cube red, flesh on the floor yellow, cube corners on the floor blue), drawn
// over everything so that points inside the flesh or behind the cube show.
#pragma once

#include "core/hand/flesh.h"
#include "core/render/draw_list.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/task/scene_layout.h"

namespace handlab::render {

struct SimDrawStyle {
  bool contacts = false;
  float contact_radius = 0.0015f;  // m
  Eigen::Vector4f skin{0.86f, 0.67f, 0.56f, 1.0f};
  Eigen::Vector4f hand_on_cube{0.90f, 0.10f, 0.12f, 1.0f};
  Eigen::Vector4f hand_on_floor{0.95f, 0.80f, 0.10f, 1.0f};
  Eigen::Vector4f cube_on_floor{0.15f, 0.35f, 0.95f, 1.0f};
};

// `layout` places the zones and sizes the cube (its pose is the state's).
DrawList draw_sim_state(const task::SceneLayout& layout, const hand::HandFlesh& flesh,
                        const sim::HandSimModel& model, const sim::HandSimState& state,
                        const SimDrawStyle& style = {});

}  // namespace handlab::render
