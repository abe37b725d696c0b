// Offscreen OpenGL 3.3 core rendering through OSMesa (software, no display needed).
// Lives in its own library, handlab_offscreen, so that the Qt app never links OSMesa.
#pragma once

#include <memory>

#include "core/render/draw_list.h"
#include "core/render/image.h"
#include "core/render/orbit_camera.h"
#include "core/render/view_camera.h"

namespace handlab::render {

class OffscreenRenderer {
 public:
  // samples: multisample anti-aliasing (1 = none). Throws std::runtime_error when OSMesa
  // cannot create a 3.3 core context.
  OffscreenRenderer(int width, int height, int samples = 4);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  Image render(const DrawList& list, const OrbitCamera& camera);
  Image render(const DrawList& list, const ViewCamera& camera);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace handlab::render
