#include "app/gui/scene_view.h"

#include <memory>

#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <QPainter>
#include <QVBoxLayout>
#include <QWheelEvent>

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

// Draws the scene with the core renderer; owned by a SceneView, which feeds it the camera.
class SceneCanvas : public QOpenGLWidget {
 public:
  explicit SceneCanvas(SceneView* view) : QOpenGLWidget(view), view_(view) {
    setAttribute(Qt::WA_TransparentForMouseEvents);  // the SceneView handles input
  }
  ~SceneCanvas() override { release(); }

  QString error() const { return error_; }

 protected:
  void initializeGL() override {
    QOpenGLContext* gl = context();
    connect(gl, &QOpenGLContext::aboutToBeDestroyed, this, [this] { release(); });
    try {
      renderer_ = std::make_unique<render::Renderer>(
          [gl](const char* name) -> render::GlProc { return gl->getProcAddress(name); });
    } catch (const std::exception& e) {
      error_ = QString::fromUtf8(e.what());
      qWarning("handlab: 3D view unavailable: %s", e.what());
    }
  }

  void paintGL() override {
    if (!renderer_) return;
    const qreal ratio = devicePixelRatioF();
    if (const auto& frame = view_->frame()) {
      renderer_->render(*frame, view_->camera(), int(width() * ratio), int(height() * ratio));
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
    renderer_->render(list, view_->camera(), int(width() * ratio), int(height() * ratio));
  }

 private:
  void release() {
    if (!renderer_) return;
    makeCurrent();  // GL objects are deleted with their context current
    renderer_.reset();
    doneCurrent();
  }

  SceneView* view_;
  std::unique_ptr<render::Renderer> renderer_;
  QString error_;
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
    canvas_ = new SceneCanvas(this);
    // The view multisamples in its own framebuffer, not the window's, and not at all on a
    // software renderer, where every sample costs CPU time the display's latency needs.
    QSurfaceFormat format = canvas_->format();
    format.setSamples(opengl_probe().software ? 0 : 4);
    canvas_->setFormat(format);
    connect(canvas_, &QOpenGLWidget::frameSwapped, this, &SceneView::picture_shown);
    auto* box = new QVBoxLayout(this);
    box->setContentsMargins(0, 0, 0, 0);
    box->addWidget(canvas_);
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

QImage SceneView::grab_picture() {
  return canvas_ ? canvas_->grabFramebuffer() : QImage();
}

void SceneView::redraw() {
  if (canvas_)
    canvas_->update();
  else
    update();
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
