// What one frame draws: meshes with a model transform, a colour and a shading style.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/render/image.h"
#include "core/render/render_mesh.h"

namespace handlab::render {

// kPicture: unlit, coloured by `picture` laid over the mesh's square x, y in [-0.5, 0.5]
// (make_panel_mesh), its top row at y = 0.5.
enum class Shading { kLit, kCheckerFloor, kUnlit, kPicture };

struct DrawItem {
  std::shared_ptr<const RenderMesh> mesh;
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
  Eigen::Vector4f color{0.8f, 0.8f, 0.8f, 1.0f};
  Shading shading = Shading::kLit;
  // Meshes whose vertices change every frame (deforming skin) are uploaded again each frame;
  // static ones once, cached by address.
  bool dynamic = false;
  // Drawn after the others and over them (no depth test): markers that must stay visible,
  // such as contact points inside the flesh.
  bool overlay = false;
  // Lies on the ground, the plane y = 0 (the floor and what is painted on it). The renderer
  // keeps the ground's picture while the camera and these items stay as they are, and draws
  // the rest clipped to y >= 0 over it; ground items come first in the list.
  bool ground = false;
  // With kPicture: its picture (uploaded once, cached by address, as static meshes are).
  std::shared_ptr<const Image> picture = nullptr;
};

struct DrawList {
  std::vector<DrawItem> items;
  Eigen::Vector3f background{0.157f, 0.173f, 0.204f};  // linear RGB of the clear colour
};

}  // namespace handlab::render
