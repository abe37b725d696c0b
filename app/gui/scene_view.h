// The live 3D view: the core renderer on an OpenGL canvas, with an orbit camera (left drag
// orbits, wheel zooms). Input is handled here, so the camera works the same whether or not
// the platform offers OpenGL; without it the view says so instead of drawing.
#pragma once

#include <memory>

#include <QPoint>
#include <QWidget>

#include <Eigen/Geometry>

#include "core/render/draw_list.h"
#include "core/render/orbit_camera.h"
#include "core/task/scene_layout.h"

class QWindow;

namespace handlab::gui {

class SceneCanvas;

class SceneView : public QWidget {
  Q_OBJECT

 public:
  explicit SceneView(QWidget* parent = nullptr);
  ~SceneView() override;

  const render::OrbitCamera& camera() const { return camera_; }
  void set_camera(const render::OrbitCamera& camera);
  void set_layout(const task::SceneLayout& layout);
  const task::SceneLayout& layout() const { return layout_; }
  // The study's simulated hand (skin) and a tracked Leap skeleton, in their rest poses.
  void set_show_hands(bool show);
  bool show_hands() const { return show_hands_; }
  // Where the simulated hand's palm centre is drawn (scene coordinates), for tests.
  static Eigen::Vector3f simulated_palm_position();
  // A frame to show instead of the static scene (a simulation's state); null: the scene.
  void set_frame(std::shared_ptr<const render::DrawList> frame);
  const std::shared_ptr<const render::DrawList>& frame() const { return frame_; }
  // The native window the scene is drawn in, where the mouse lands; null when the platform
  // has no OpenGL 3.3 (e.g. the offscreen platform).
  QWindow* canvas() const;
  // The picture as the view draws it now, drawn off screen at the view's size (so the view
  // need not be shown); empty without OpenGL.
  QImage grab_picture();

 signals:
  void camera_changed();
  // A picture is on screen: the window's composition and buffer swap returned.
  void picture_shown();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  void redraw();

  render::OrbitCamera camera_;
  task::SceneLayout layout_;
  SceneCanvas* canvas_ = nullptr;
  QPoint last_mouse_;
  bool dragging_ = false;
  bool show_hands_ = true;
  std::shared_ptr<const render::DrawList> frame_;
};

// A picture of `widget` as it is on screen, its 3D views drawn in (QWidget::grab leaves out
// the native windows they draw in).
QImage grab_with_views(QWidget* widget);

// True when an OpenGL 3.3 core context can be created on this platform (checked once).
bool opengl_available();

}  // namespace handlab::gui
