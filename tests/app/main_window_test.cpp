#include <QMenuBar>
#include <QTest>

#include <gtest/gtest.h>

#include "app/gui/main_window.h"
#include "app/gui/scene_view.h"

namespace handlab::gui {
namespace {

TEST(MainWindow, HasTheFourMenus) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  QStringList titles;
  for (QAction* action : window.menuBar()->actions()) titles << action->text().remove('&');
  EXPECT_EQ(titles, (QStringList{"File", "Study", "Analysis", "Help"}));
}

TEST(MainWindow, MouseDragOrbitsTheCamera) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  SceneView* view = window.scene_view();
  const render::OrbitCamera before = view->camera();

  const QPoint start = view->rect().center();
  QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, start);
  QTest::mouseMove(view, start + QPoint(60, 0));
  QTest::mouseMove(view, start + QPoint(120, 40));
  QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, start + QPoint(120, 40));

  const render::OrbitCamera after = view->camera();
  EXPECT_NEAR(after.yaw, before.yaw - 120 * 0.01f, 1e-5f);  // left-right drag turns about +y
  EXPECT_NEAR(after.pitch, before.pitch + 40 * 0.01f, 1e-5f);
  EXPECT_EQ(after.distance, before.distance);

  // Moving without a pressed button changes nothing.
  QTest::mouseMove(view, start);
  EXPECT_EQ(view->camera().yaw, after.yaw);
}

TEST(MainWindow, WheelZooms) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  SceneView* view = window.scene_view();
  const float before = view->camera().distance;
  const QPointF at = view->rect().center();
  QWheelEvent wheel(at, view->mapToGlobal(at), QPoint(), QPoint(0, 240), Qt::NoButton,
                    Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(view, &wheel);
  EXPECT_NEAR(view->camera().distance, before * 0.81f, 1e-5f);
}

}  // namespace
}  // namespace handlab::gui

namespace handlab::gui {
namespace {

// Runs where the platform has OpenGL (CTest runs it once more under Xvfb): the live view
// draws the same scene as the offscreen renderer.
TEST(SceneViewGl, DrawsTheSceneInAWindow) {
  if (!opengl_available())
    GTEST_SKIP() << "no OpenGL on platform " << qPrintable(QGuiApplication::platformName());
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  SceneView* view = window.scene_view();
  ASSERT_NE(view->canvas(), nullptr);
  const QImage picture = view->grab_picture();
  ASSERT_FALSE(picture.isNull());
  // The cube's top-face centre, projected with the view's own camera.
  task::SceneLayout layout = view->layout();
  Eigen::Vector2f p;
  const Eigen::Vector3f top =
      layout.zone_a.cast<float>() + Eigen::Vector3f(0, float(layout.cube_size), 0);
  ASSERT_TRUE(render::project_to_pixel(view->camera(), picture.width(), picture.height(), top, &p));
  const QColor cube = picture.pixelColor(int(p.x()), int(p.y()));
  EXPECT_GT(cube.red(), cube.green() + 60) << qPrintable(cube.name());
  EXPECT_GT(cube.green(), cube.blue() + 30) << qPrintable(cube.name());
  // The simulated hand's skin over its palm centre.
  ASSERT_TRUE(render::project_to_pixel(view->camera(), picture.width(), picture.height(),
                                       SceneView::simulated_palm_position(), &p));
  const QColor skin = picture.pixelColor(int(p.x()), int(p.y()));
  EXPECT_GT(skin.red(), 150) << qPrintable(skin.name());
  EXPECT_GT(skin.red(), skin.green() + 20) << qPrintable(skin.name());
  EXPECT_GT(skin.green(), skin.blue()) << qPrintable(skin.name());
}

}  // namespace
}  // namespace handlab::gui
