#include <QMenuBar>
#include <QTest>

#include <gtest/gtest.h>

#include "app/gui/main_window.h"
#include "app/gui/scene_view.h"
#include "app/gui/study_panel.h"
#include "core/store/study_store.h"
#include "studies/session/session_runner.h"

#include <QDockWidget>
#include <QTableWidget>
#include <filesystem>

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

TEST(MainWindow, ShowsAStudyDatabasesProgress) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/gui_study.db";
  for (const char* side : {"", "-wal", "-shm"}) std::filesystem::remove(path + side);
  const studies::Protocol protocol = studies::read_protocol(std::string(HANDLAB_SOURCE_DIR) +
                                                            "/studies/fine-manipulation-2021.json");
  store::StudyStore::create(path, studies::study_definition(protocol));
  {
    store::StudyStore db(path);
    store::Participant p;
    p.id = "P07";
    p.age = 31;
    p.sex = "M";
    p.handedness = "left";
    p.hand_length = 0.2;
    p.vr_experience = "none";
    db.add_participant(p, studies::planned_rows(protocol, "P07", 0));
    db.skip_trial("P07", 0, db.begin_session("P07", "gui test"), "demo");
  }
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.show_study(QString::fromStdString(path)), QString());
  auto* dock = window.findChild<QDockWidget*>("study");
  ASSERT_NE(dock, nullptr);
  auto* panel = qobject_cast<StudyPanel*>(dock->widget());
  ASSERT_NE(panel, nullptr);
  QTableWidget* table = panel->table();
  ASSERT_EQ(table->rowCount(), 1);
  EXPECT_EQ(table->item(0, 0)->text(), "P07");
  EXPECT_EQ(table->item(0, 1)->text(), "24");
  EXPECT_EQ(table->item(0, 3)->text(), "1");
  EXPECT_TRUE(table->item(0, 5)->text().startsWith("2: "))
      << table->item(0, 5)->text().toStdString();

  EXPECT_NE(window.show_study("/no/such/study.db"), QString());
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
