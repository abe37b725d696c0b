// Draws a DrawList with OpenGL 3.3 core into whatever framebuffer the caller has bound.
// The same code serves the Qt view (an OpenGL window) and offscreen pictures (OSMesa).
#pragma once

#include <memory>
#include <string>

#include "core/render/draw_list.h"
#include "core/render/gl_loader.h"
#include "core/render/orbit_camera.h"
#include "core/render/view_camera.h"

namespace handlab::render {

class Renderer {
 public:
  // Needs a current OpenGL 3.3 core context; throws std::runtime_error if shaders fail.
  explicit Renderer(const GlLoader& loader);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void render(const DrawList& list, const OrbitCamera& camera, int width, int height);
  void render(const DrawList& list, const ViewCamera& camera, int width, int height);

  // "vendor / renderer / version" of the context, for logs.
  std::string context_description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace handlab::render
