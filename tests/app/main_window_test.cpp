#include <QMenuBar>
#include <QProcess>
#include <QSignalSpy>
#include <QTest>
#include <QWindow>

#include <gtest/gtest.h>

#include "app/gui/main_window.h"
#include "app/gui/participants_page.h"
#include "app/gui/pinch_simulation.h"
#include "app/gui/scene_view.h"
#include "core/render/scene_drawing.h"
#include "core/store/study_store.h"
#include "studies/session/session_runner.h"
#include "tests/app/view_cells.h"
#include "tests/support/test_participant.h"

#include <QDockWidget>
#include <QTableView>
#include <filesystem>

using handlab::gui::testing::view_cell;
using handlab::gui::testing::view_rows;

namespace handlab::gui {
namespace {

// The app's own options reach it: --participant-view is not Qt's -display (which took
// `--display headset` for an X server), and --list-xr without a runtime says so in one line.
TEST(AppCommandLine, TakesItsHeadsetOptions) {
  QProcess bad;
  bad.start(HANDLAB_APP, {"--participant-view", "helmet"});
  ASSERT_TRUE(bad.waitForFinished(30000));
  EXPECT_EQ(bad.exitCode(), 2);
  const QString said = QString::fromUtf8(bad.readAllStandardError());
  EXPECT_TRUE(said.contains("--participant-view is window or headset")) << said.toStdString();

  QProcess list;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("XR_RUNTIME_JSON", QString(HANDLAB_TEST_TMP) + "/no-such-runtime.json");
  list.setProcessEnvironment(env);
  list.start(HANDLAB_APP, {"--list-xr"});
  ASSERT_TRUE(list.waitForFinished(30000));
  EXPECT_EQ(list.exitCode(), 1);
  EXPECT_EQ(QString::fromUtf8(list.readAllStandardError()),
            "handlab: no OpenXR runtime answered: XR_ERROR_RUNTIME_UNAVAILABLE (docs/hmd.md says "
            "how to start one)\n");
}

TEST(MainWindow, HasItsMenus) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  QStringList titles;
  for (QAction* action : window.menuBar()->actions()) titles << action->text().remove('&');
  EXPECT_EQ(titles, (QStringList{"File", "Session", "View", "Simulation", "Analysis", "Help"}));
}

// The scripted pinch runs on the simulator in the background and the view shows its newest
// state: the task scene with the cube where the simulation has it, the deforming skin and,
// on request, the contact points (here the 1 cm cube's four corners on the floor, drawn over
// everything).
TEST(MainWindow, ShowsTheSimulatedPinch) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  SceneView* view = window.scene_view();
  task::SceneLayout layout = view->layout();
  layout.cube_size = 0.01;
  view->set_layout(layout);
  window.set_show_contacts(true);
  PinchSimulation* pinch = window.start_pinch(0.25);
  ASSERT_NE(pinch, nullptr);
  ASSERT_TRUE(QTest::qWaitFor([&] { return pinch->finished(); }, 120000));
  QTest::qWait(50);  // the queued notifications
  EXPECT_TRUE(pinch->error().isEmpty()) << pinch->error().toStdString();
  EXPECT_NEAR(pinch->progress().time, 0.25, 1e-9);
  ASSERT_NE(view->frame(), nullptr);
  const render::DrawList scene =
      render::draw_task_scene(view->layout(), task::cube_start_pose(view->layout()));
  const std::vector<render::DrawItem>& items = view->frame()->items;
  ASSERT_EQ(items.size(), scene.items.size() + 1 + 4);  // the skin, four corners
  int overlays = 0, dynamic = 0;
  for (const render::DrawItem& item : items) {
    overlays += item.overlay;
    dynamic += item.dynamic;
  }
  EXPECT_EQ(overlays, 4);
  EXPECT_EQ(dynamic, 1);  // the skin, uploaded anew with every state
  // Hiding the contact points redraws the same state without them; stopping returns the view
  // to the static scene.
  window.set_show_contacts(false);
  EXPECT_EQ(view->frame()->items.size(), scene.items.size() + 1);
  window.start_pinch(0.0);  // a second run replaces the first
  QTest::qWait(100);
  window.stop_pinch();  // mid-run: joins the worker without waiting for the script's end
  EXPECT_EQ(window.pinch(), nullptr);
  EXPECT_EQ(view->frame(), nullptr);
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
  QTableView* table = window.participants()->table();
  ASSERT_EQ(view_rows(table), 1);
  EXPECT_EQ(view_cell(table, 0, 0), "P07");
  EXPECT_EQ(view_cell(table, 0, 4), "20.0") << "hand length in cm";
  EXPECT_EQ(view_cell(table, 0, 8), "1 / 20");
  // The skip opened a session it never ended: the app calls it interrupted.
  EXPECT_TRUE(view_cell(table, 0, 9).contains("resume at trial 2"))
      << view_cell(table, 0, 9).toStdString();
  EXPECT_TRUE(window.windowTitle().startsWith("gui_study.db"));

  EXPECT_NE(window.show_study("/no/such/study.db"), QString());
}

// A simulated study merged from some of its parts says so on its page.
TEST(MainWindow, SaysAStudyIsPartial) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/gui_partial.db";
  for (const char* side : {"", "-wal", "-shm"}) std::filesystem::remove(path + side);
  const studies::Protocol protocol = studies::read_protocol(std::string(HANDLAB_SOURCE_DIR) +
                                                            "/studies/fine-manipulation-2021.json");
  store::StudyDefinition definition = studies::study_definition(protocol);
  definition.planned_participants = 3;  // of whom only the second is here
  store::StudyStore::create(path, definition);
  {
    store::StudyStore db(path);
    store::Participant p = test::participant("S02");
    p.simulated = true;
    db.add_participant(p, studies::planned_rows(protocol, "S02", 1), 1);
  }
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_EQ(window.show_study(QString::fromStdString(path)), QString());
  auto* summary = window.findChild<QTableView*>("study_summary");
  ASSERT_NE(summary, nullptr);
  QString said;
  for (int row = 0; row < view_rows(summary); ++row)
    if (view_cell(summary, row, 0) == "Partial study") said = view_cell(summary, row, 1);
  EXPECT_TRUE(said.startsWith("1 of 3 planned participants (missing enrolment places 1, 3)"))
      << said.toStdString();
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

// The scene is drawn in a window of its own: the mouse lands there and still moves the
// camera, and a new frame is drawn and reported on screen without waiting for other events.
TEST(SceneViewGl, TheDrawingWindowTakesTheMouseAndShowsEachNewFrame) {
  if (!opengl_available())
    GTEST_SKIP() << "no OpenGL on platform " << qPrintable(QGuiApplication::platformName());
  SceneView scene;
  SceneView* view = &scene;
  view->resize(640, 480);
  view->show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(view));
  QWindow* canvas = view->canvas();
  ASSERT_NE(canvas, nullptr);
  ASSERT_TRUE(QTest::qWaitForWindowExposed(canvas));
  EXPECT_NE(canvas->parent(), nullptr) << "embedded in the view, not a window of its own";

  const render::OrbitCamera before = view->camera();
  const QPoint start(canvas->width() / 2, canvas->height() / 2);
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, start);
  QTest::mouseMove(canvas, start + QPoint(50, 0));
  QTest::mouseMove(canvas, start + QPoint(100, 30));
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, start + QPoint(100, 30));
  EXPECT_NEAR(view->camera().yaw, before.yaw - 100 * 0.01f, 1e-5f);
  EXPECT_NEAR(view->camera().pitch, before.pitch + 30 * 0.01f, 1e-5f);

  QSignalSpy shown(view, &SceneView::picture_shown);
  const task::SceneLayout layout = view->layout();
  auto new_frame = [&] {
    view->set_frame(std::make_shared<const render::DrawList>(
        render::draw_task_scene(layout, task::cube_start_pose(layout))));
  };
  for (int i = 0; i < 3; ++i) {
    new_frame();
    ASSERT_TRUE(shown.wait(2000)) << "frame " << i;
  }
  // A screenshot of the window has the scene in it (QWidget::grab alone leaves it out).
  const QImage composed = grab_with_views(&scene);
  Eigen::Vector2f p;
  const Eigen::Vector3f top =
      layout.zone_a.cast<float>() + Eigen::Vector3f(0, float(layout.cube_size), 0);
  ASSERT_TRUE(
      render::project_to_pixel(view->camera(), composed.width(), composed.height(), top, &p));
  const QColor cube = composed.pixelColor(int(p.x()), int(p.y()));
  EXPECT_GT(cube.red(), cube.blue() + 60) << qPrintable(cube.name());

  // Requests made before the picture is drawn are one picture.
  const int drawn = int(shown.count());
  for (int i = 0; i < 5; ++i) new_frame();
  QTest::qWait(200);
  EXPECT_EQ(shown.count(), drawn + 1);
}

}  // namespace
}  // namespace handlab::gui
