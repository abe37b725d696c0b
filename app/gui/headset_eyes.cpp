#include "app/gui/headset_eyes.h"

#include <algorithm>
#include <stdexcept>

#include <QImage>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QSurfaceFormat>

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
    }
  }

  render::Image draw(const render::DrawList& scene, const render::ViewCamera& camera) {
    if (!context_.makeCurrent(surface_))
      throw std::runtime_error("the headset's eyes: the OpenGL context was lost");
    target_->bind();
    renderer_->render(scene, camera, target_->width(), target_->height());
    const QImage picture = target_->toImage().convertToFormat(QImage::Format_RGBA8888);
    target_->release();
    context_.doneCurrent();
    render::Image image;
    image.width = picture.width();
    image.height = picture.height();
    image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
    const std::size_t row = std::size_t(image.width) * 4;
    for (int y = 0; y < image.height; ++y)
      std::copy_n(picture.constScanLine(y), row, image.rgba.data() + std::size_t(y) * row);
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
