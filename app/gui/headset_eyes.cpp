#include "app/gui/headset_eyes.h"

#include <stdexcept>

#include <QImage>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QSurfaceFormat>

#include "app/gui/qt_image.h"
#include "core/render/renderer.h"

namespace handlab::gui {
namespace {

// One eye size's context, framebuffer and renderer, made and used on one thread.
class EyeRenderer {
 public:
  EyeRenderer(QOffscreenSurface* surface, int width, int height) : surface_(surface) {
    context_.setFormat(surface->format());
    if (!context_.create() || !context_.makeCurrent(surface_))
      throw std::runtime_error("the headset's eyes: no OpenGL context on this display");
    QOpenGLFramebufferObjectFormat format;
    format.setAttachment(QOpenGLFramebufferObject::CombinedDepthStencil);
    format.setSamples(4);  // as the CLI's offscreen drawing
    target_ = std::make_unique<QOpenGLFramebufferObject>(width, height, format);
    QOpenGLContext* gl = &context_;
    renderer_ = std::make_unique<render::Renderer>(
        [gl](const char* name) -> render::GlProc { return gl->getProcAddress(name); });
    context_.doneCurrent();
  }
  ~EyeRenderer() {
    if (context_.makeCurrent(surface_)) {  // GL objects go with their context current
      renderer_.reset();
      target_.reset();
      context_.doneCurrent();
    } else {  // no context to delete them in: left to the context's own end
      (void)renderer_.release();
      (void)target_.release();
    }
  }

  render::Image draw(const render::DrawList& scene, const render::ViewCamera& camera) {
    if (!context_.makeCurrent(surface_))
      throw std::runtime_error("the headset's eyes: the OpenGL context was lost");
    target_->bind();
    renderer_->render(scene, camera, target_->width(), target_->height());
    QImage picture = target_->toImage();
    target_->release();
    context_.doneCurrent();
    // The bytes as drawn: a premultiplied picture is read as it is, not divided by its alpha.
    if (picture.format() == QImage::Format_RGBA8888_Premultiplied)
      picture.reinterpretAsFormat(QImage::Format_RGBA8888);
    render::Image image = image_of(picture);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;  // opaque
    return image;
  }

 private:
  QOffscreenSurface* surface_;
  QOpenGLContext context_;
  std::unique_ptr<QOpenGLFramebufferObject> target_;
  std::unique_ptr<render::Renderer> renderer_;
};

}  // namespace

HeadsetEyes::HeadsetEyes() : surface_(std::make_unique<QOffscreenSurface>()) {
  surface_->setFormat(QSurfaceFormat::defaultFormat());
  surface_->create();
  if (!surface_->isValid())
    throw std::runtime_error("the headset's eyes: no offscreen OpenGL surface on this display");
}

HeadsetEyes::~HeadsetEyes() = default;

xr::HeadsetView::DrawerFactory HeadsetEyes::factory() const {
  return [surface = surface_.get()](int width, int height) {
    auto eye = std::make_shared<EyeRenderer>(surface, width, height);
    return [eye](const render::DrawList& scene, const render::ViewCamera& camera) {
      return eye->draw(scene, camera);
    };
  };
}

}  // namespace handlab::gui
