// What a trial looks like at one step, from the record the frame log keeps of it: the task
// scene with the cube where it was and the simulated hand's bones where they were, or, on
// the soft hand while it runs, its skin where the flesh was. The app's live view, its
// participant window and replays of stored trials draw this.
#pragma once

#include <vector>

#include "core/hand/flesh.h"
#include "core/render/draw_list.h"
#include "core/render/hand_drawing.h"
#include "core/store/frame_record.h"
#include "core/task/scene_layout.h"

namespace handlab::render {

// `layout` places the zones and sizes the cube; `hand` holds the condition's simulated hand's
// bone meshes (make_bone_meshes).
DrawList draw_stored_frame(const task::SceneLayout& layout, const BoneMeshes& hand,
                           const store::FrameRecord& frame);

// The soft hand as its skin: `skin`, the flesh's render surface embedded in its `tets`, placed
// by the flesh's nodes at `flesh_nodes` (the step `frame` records; the frame places the cube).
DrawList draw_soft_hand_frame(const task::SceneLayout& layout, const hand::EmbeddedSurface& skin,
                              const mesh::TetMesh& tets,
                              const std::vector<Eigen::Vector3d>& flesh_nodes,
                              const store::FrameRecord& frame);

}  // namespace handlab::render
