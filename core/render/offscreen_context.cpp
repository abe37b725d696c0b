#include "core/render/offscreen_context.h"

// gl_functions.h (glcorearb.h) first: osmesa.h pulls in GL/gl.h, which would hide the
// OpenGL 1.x function-pointer types that glcorearb.h declares.
#include "core/render/gl_functions.h"

#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "core/render/renderer.h"

namespace handlab::render {
namespace {

GlProc osmesa_loader(const char* name) {
  return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
}

}  // namespace

struct OffscreenRenderer::Impl {
  int width, height, samples;
  OSMesaContext context = nullptr;
  std::vector<std::uint8_t> buffer;  // OSMesa's framebuffer, bottom row first
  std::unique_ptr<GlFunctions> gl;
  std::unique_ptr<Renderer> renderer;
  GLuint fbo = 0, color_rb = 0, depth_rb = 0;

  Impl(int w, int h, int s) : width(w), height(h), samples(s) {
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384)
      throw std::runtime_error("offscreen size must be between 1 and 16384 pixels");
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context) throw std::runtime_error("OSMesa could not create an OpenGL 3.3 core context");
    buffer.resize(std::size_t(w) * std::size_t(h) * 4);
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, w, h)) {
      OSMesaDestroyContext(context);
      throw std::runtime_error("OSMesaMakeCurrent failed");
    }
    gl = std::make_unique<GlFunctions>(osmesa_loader);
    renderer = std::make_unique<Renderer>(osmesa_loader);
    if (samples > 1) create_multisample_target();
  }

  ~Impl() {
    renderer.reset();
    if (fbo) {
      gl->DeleteFramebuffers(1, &fbo);
      gl->DeleteRenderbuffers(1, &color_rb);
      gl->DeleteRenderbuffers(1, &depth_rb);
    }
    OSMesaDestroyContext(context);
  }

  void create_multisample_target() {
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->GenRenderbuffers(1, &color_rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, color_rb);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb);
    gl->GenRenderbuffers(1, &depth_rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width,
                                       height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      // Fall back to the plain OSMesa buffer: aliased, but correct.
      gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
      gl->DeleteFramebuffers(1, &fbo);
      gl->DeleteRenderbuffers(1, &color_rb);
      gl->DeleteRenderbuffers(1, &depth_rb);
      fbo = 0;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

OffscreenRenderer::OffscreenRenderer(int width, int height, int samples)
    : impl_(std::make_unique<Impl>(width, height, samples)) {}
OffscreenRenderer::~OffscreenRenderer() = default;

Image OffscreenRenderer::render(const DrawList& list, const OrbitCamera& camera) {
  return render(list, view_camera(camera, float(impl_->width) / float(impl_->height)));
}

Image OffscreenRenderer::render(const DrawList& list, const ViewCamera& camera) {
  Impl& s = *impl_;
  OSMesaMakeCurrent(s.context, s.buffer.data(), GL_UNSIGNED_BYTE, s.width, s.height);
  s.gl->BindFramebuffer(GL_FRAMEBUFFER, s.fbo);
  s.renderer->render(list, camera, s.width, s.height);
  if (s.fbo) {
    s.gl->BindFramebuffer(GL_READ_FRAMEBUFFER, s.fbo);
    s.gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    s.gl->BlitFramebuffer(0, 0, s.width, s.height, 0, 0, s.width, s.height, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
    s.gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  s.gl->Finish();

  Image image;
  image.width = s.width;
  image.height = s.height;
  image.rgba.resize(s.buffer.size());
  const std::size_t row = std::size_t(s.width) * 4;
  for (int y = 0; y < s.height; ++y) {  // OSMesa's rows run bottom-up
    std::copy_n(s.buffer.data() + std::size_t(s.height - 1 - y) * row, row,
                image.rgba.data() + std::size_t(y) * row);
  }
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  return image;
}

}  // namespace handlab::render
