#include "app/gui/scene_view.h"

#include <functional>
#include <memory>

#include <QCoreApplication>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>
#include <QPainter>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <QWindow>

#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/hand/tracked_hand.h"
#include "core/render/hand_drawing.h"
#include "core/render/renderer.h"
#include "core/render/scene_drawing.h"

namespace handlab::gui {
namespace {

// Palm down, fingers pointing away from the default camera, over the given point.
Eigen::Isometry3d hand_placement(const Eigen::Vector3d& at) {
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  placement.linear() << -1, 0, 0, 0, 0, -1, 0, -1, 0;
  placement.translation() = at;
  return placement;
}

const Eigen::Vector3d kSimulatedHandAt(-0.12, 0.14, 0.12);
const Eigen::Vector3d kTrackedHandAt(0.16, 0.14, 0.12);

// The hands are built once: the study hand's skin (21.4 cm) and an 18 cm tracked skeleton.
struct HandModels {
  hand::Skeleton simulated;
  hand::HandSkin skin;
  hand::Skeleton tracked;
  HandModels() {
    const hand::HandShape study = hand::HandShape::with_length(0.214);
    simulated = hand::build_simulated_hand(study);
    skin = hand::build_skin(simulated, study, 2);
    tracked = hand::build_tracked_hand(hand::HandShape::with_length(0.18));
  }
};

const HandModels& hand_models() {
  static const HandModels models;
  return models;
}

}  // namespace

Eigen::Vector3f SceneView::simulated_palm_position() {
  return (hand_placement(kSimulatedHandAt) * Eigen::Vector3d(0, 0.25 * 0.214, 0)).cast<float>();
}

// Draws the scene with the core renderer into a native window of its own, embedded in the
// SceneView. A window, not a QOpenGLWidget: a widget's picture is composed into its top-level
// window on every frame (the whole window drawn again from textures), which on a software
// renderer costs twice the scene itself; a window of its own swaps just its own pixels. It
// draws as soon as the event loop is free after a request, not at the platform's next update
// tick (5 ms later on X11): the live view's latency counts every millisecond. Input goes to
// the SceneView (its event filter).
class SceneCanvas : public QWindow {
 public:
  SceneCanvas(SceneView* view, std::function<void()> shown)
      : view_(view), shown_(std::move(shown)) {
    setSurfaceType(QSurface::OpenGLSurface);
    setFlag(Qt::WindowDoesNotAcceptFocus);  // keys stay with the widgets and their shortcuts
  }
  ~SceneCanvas() override {
    if (context_ && renderer_ && context_->makeCurrent(this)) {
      renderer_.reset();  // GL objects are deleted with their context current
      context_->doneCurrent();
    }
  }

  // Coalesced: requests made before the picture is drawn are one picture.
  void request_picture() {
    if (pending_) return;
    pending_ = true;
    QCoreApplication::postEvent(this, new QEvent(QEvent::UpdateRequest));
  }

  // The picture as it would be drawn now, at the view's size, drawn off screen (the view
  // need not be shown).
  QImage grab(const QSize& size) {
    if (!create_context()) return {};
    QOffscreenSurface surface;
    surface.setFormat(context_->format());
    surface.create();
    if (!context_->makeCurrent(&surface) || !create_renderer()) return {};
    QImage image;
    {
      QOpenGLFramebufferObject target(size, QOpenGLFramebufferObject::CombinedDepthStencil);
      target.bind();
      draw(size);
      image = target.toImage();
      target.release();
    }
    context_->doneCurrent();
    return image;
  }

 protected:
  bool event(QEvent* event) override {
    if (event->type() == QEvent::UpdateRequest) {
      pending_ = false;
      show_picture();
      return true;
    }
    return QWindow::event(event);
  }

  void exposeEvent(QExposeEvent*) override {
    if (isExposed()) show_picture();
  }

 private:
  QSize pixel_size() const { return size() * devicePixelRatio(); }

  bool create_context() {
    if (failed_) return false;
    if (!context_) {
      context_ = std::make_unique<QOpenGLContext>();
      context_->setFormat(requestedFormat());
      if (!context_->create()) {
        failed_ = true;
        return false;
      }
    }
    return true;
  }

  // With the context current.
  bool create_renderer() {
    if (renderer_) return true;
    QOpenGLContext* gl = context_.get();
    try {
      renderer_ = std::make_unique<render::Renderer>(
          [gl](const char* name) -> render::GlProc { return gl->getProcAddress(name); });
    } catch (const std::exception& e) {
      failed_ = true;
      qWarning("handlab: 3D view unavailable: %s", e.what());
      context_->doneCurrent();
      return false;
    }
    return true;
  }

  void show_picture() {
    if (!isExposed() || !create_context() || !context_->makeCurrent(this) || !create_renderer())
      return;
    draw(pixel_size());
    context_->swapBuffers(this);
    if (shown_) shown_();
  }

  void draw(const QSize& size) {
    if (const auto& frame = view_->frame()) {
      renderer_->render(*frame, view_->camera(), size.width(), size.height());
      return;
    }
    const task::SceneLayout& layout = view_->layout();
    render::DrawList list = render::draw_task_scene(layout, task::cube_start_pose(layout));
    if (view_->show_hands()) {
      const HandModels& hands = hand_models();
      render::draw_skin(list, hands.skin.surface.vertices, hands.skin.surface.triangles,
                        hand_placement(kSimulatedHandAt), {0.86f, 0.67f, 0.56f, 1.0f});
      render::draw_skeleton(list, hands.tracked, hand::HandPose::rest(hands.tracked),
                            hand_placement(kTrackedHandAt), {0.35f, 0.6f, 0.85f, 1.0f},
                            {0.95f, 0.95f, 0.95f, 1.0f});
    }
    renderer_->render(list, view_->camera(), size.width(), size.height());
  }

  SceneView* view_;
  std::function<void()> shown_;
  std::unique_ptr<QOpenGLContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
  bool pending_ = false, failed_ = false;
};

namespace {

struct OpenGlProbe {
  bool available = false;
  bool software = false;  // llvmpipe, softpipe or swrast: every pixel costs CPU time
};

const OpenGlProbe& opengl_probe() {
  static const OpenGlProbe probe = [] {
    OpenGlProbe result;
    QOpenGLContext context;
    context.setFormat(QSurfaceFormat::defaultFormat());
    if (!context.create() || context.format().version() < qMakePair(3, 3)) return result;
    result.available = true;
    QOffscreenSurface surface;
    surface.setFormat(context.format());
    surface.create();
    if (context.makeCurrent(&surface)) {
      const auto* name =
          reinterpret_cast<const char*>(context.functions()->glGetString(GL_RENDERER));
      const QString renderer = name ? QString::fromLatin1(name) : QString();
      result.software = renderer.contains("llvmpipe") || renderer.contains("softpipe") ||
                        renderer.contains("swrast");
      context.doneCurrent();
    }
    return result;
  }();
  return probe;
}

}  // namespace

bool opengl_available() {
  return opengl_probe().available;
}

SceneView::SceneView(QWidget* parent) : QWidget(parent) {
  setMinimumSize(320, 240);
  setFocusPolicy(Qt::StrongFocus);
  if (opengl_available()) {
    canvas_ = new SceneCanvas(this, [this] { emit picture_shown(); });
    // Multisampled, except on a software renderer, where every sample costs CPU time the
    // display's latency needs.
    QSurfaceFormat format = QSurfaceFormat::defaultFormat();
    format.setSamples(opengl_probe().software ? 0 : 4);
    canvas_->setFormat(format);
    canvas_->installEventFilter(this);
    auto* box = new QVBoxLayout(this);
    box->setContentsMargins(0, 0, 0, 0);
    box->addWidget(QWidget::createWindowContainer(canvas_, this));
  }
}

void SceneView::set_camera(const render::OrbitCamera& camera) {
  camera_ = camera;
  emit camera_changed();
  redraw();
}

void SceneView::set_show_hands(bool show) {
  show_hands_ = show;
  redraw();
}

void SceneView::set_frame(std::shared_ptr<const render::DrawList> frame) {
  frame_ = std::move(frame);
  redraw();
}

void SceneView::set_layout(const task::SceneLayout& layout) {
  layout_ = layout;
  redraw();
}

QWindow* SceneView::canvas() const {
  return canvas_;
}

QImage SceneView::grab_picture() {
  return canvas_ ? canvas_->grab(size() * devicePixelRatioF()) : QImage();
}

QImage grab_with_views(QWidget* widget) {
  QImage picture = widget->grab().toImage();
  QPainter painter(&picture);
  QList<SceneView*> views = widget->findChildren<SceneView*>();
  if (auto* self = qobject_cast<SceneView*>(widget)) views.prepend(self);
  for (SceneView* view : views)
    if (view->isVisible() && view->canvas() && view->window() == widget->window())
      painter.drawImage(QRect(view->mapTo(widget, QPoint(0, 0)), view->size()),
                        view->grab_picture());
  return picture;
}

void SceneView::redraw() {
  if (canvas_)
    canvas_->request_picture();
  else
    update();
}

SceneView::~SceneView() {
  delete canvas_;  // its container owns it, but goes only after the members the canvas reads
}

// The drawing window's mouse is the view's: the view's own handlers take it.
bool SceneView::eventFilter(QObject* watched, QEvent* event) {
  if (watched != canvas_) return QWidget::eventFilter(watched, event);
  switch (event->type()) {
    case QEvent::MouseButtonPress:
    case QEvent::MouseMove:
    case QEvent::MouseButtonRelease:
    case QEvent::Wheel:
      return QWidget::event(event);
    default:
      return false;
  }
}

void SceneView::paintEvent(QPaintEvent*) {
  if (canvas_) return;
  QPainter painter(this);
  painter.fillRect(rect(), QColor(40, 44, 52));
  painter.setPen(Qt::white);
  painter.drawText(rect(), Qt::AlignCenter,
                   tr("The 3D view needs OpenGL 3.3, which this display lacks."));
}

void SceneView::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) {
    dragging_ = true;
    last_mouse_ = event->position().toPoint();
  }
}

void SceneView::mouseMoveEvent(QMouseEvent* event) {
  if (!dragging_ || !(event->buttons() & Qt::LeftButton)) return;
  const QPoint now = event->position().toPoint();
  const QPoint delta = now - last_mouse_;
  last_mouse_ = now;
  camera_.orbit(float(delta.x()), float(delta.y()));
  emit camera_changed();
  redraw();
}

void SceneView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) dragging_ = false;
}

void SceneView::wheelEvent(QWheelEvent* event) {
  camera_.zoom(float(event->angleDelta().y()) / 120.0f);
  emit camera_changed();
  redraw();
  event->accept();
}

}  // namespace handlab::gui
