// The app's session with the participant in an OpenXR headset: chosen in the session panel,
// one trial of the scripted participant shown in the headset, each eye's swapchain image read
// back with the cube where that eye's projection puts it, the runtime's frame loop kept, and
// the trial stored. It needs a runtime with a headset: tests/openxr/openxr-test.sh runs it
// under Xvfb on Monado's simulated headset (the plain gui_tests run leaves it out).
#include <QCheckBox>
#include <QComboBox>
#include <QLabel>
#include <QListWidget>
#include <QProcess>
#include <QSignalSpy>
#include <QTest>
#include <QTimer>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/gui/main_window.h"
#include "app/gui/questionnaire_form.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_page.h"
#include "app/gui/session_worker.h"
#include "core/render/image.h"
#include "core/render/view_camera.h"
#include "core/store/study_store.h"
#include "core/xr/headset_view.h"
#include "tests/app/enrol_p01.h"
#include "tests/support/study_protocol.h"
#include "tests/support/test_files.h"

namespace handlab::gui {
namespace {

QString session_log(const SessionPage& page) {
  QString text;
  for (int i = 0; i < page.log()->count(); ++i) text += page.log()->item(i)->text() + "\n";
  return text;
}

// A study of tests/openxr/headset-protocol.json (two 2-second trials) with P01, its protocol
// naming `session` as its sessions' defaults, open in `window`, its session panel set for P01
// on the grasp proxy.
SessionPage* headset_session(MainWindow& window, const QString& name, const std::string& session) {
  const std::string protocol = test::headset_protocol_with_session(session, name.toStdString());
  const QString db = QString::fromStdString(test::fresh_path(name.toStdString() + ".db"));
  window.show();
  EXPECT_TRUE(QTest::qWaitForWindowExposed(&window));
  EXPECT_EQ(window.create_study(QString::fromStdString(protocol), db), QString());
  testing::enrol_p01(db);
  EXPECT_EQ(window.open_study(db), QString());
  SessionPage* page = window.session();
  page->participant_box()->setCurrentText("P01");
  page->world_box()->setCurrentIndex(
      page->world_box()->findData(int(studies::WorldKind::kGraspProxy)));
  return page;
}

// The study `name`'s first trial stored, not aborted, with at least `frames` frames logged.
void expect_first_trial_stored(const std::string& name, int frames) {
  store::StudyStore store(std::string(HANDLAB_TEST_TMP) + "/" + name + ".db");
  const auto trials = store.trials("P01");
  ASSERT_GE(trials.size(), 1u);
  EXPECT_NE(trials.front().status, store::TrialStatus::kAborted);
  EXPECT_GE(trials.front().frames, frames) << "its frames logged at 120 Hz";
}

// Each eye's image as read back from the headset, where the test's runner keeps pictures.
void keep_eyes(const xr::DisplayFrame& frame, const std::string& name = "app-eye") {
  if (const char* dir = std::getenv("HANDLAB_HEADSET_SCREENSHOTS")) {
    render::write_png(frame.read_back[0], std::string(dir) + "/" + name + "-left.png");
    render::write_png(frame.read_back[1], std::string(dir) + "/" + name + "-right.png");
  }
}

// How light the headset's panel looks in the left eye: the mean of the pixels over a strip
// of it (10-16 cm up, 30 cm across, render::draw_panel's place) that the instruction's panel
// and the questionnaire's both cover.
double panel_lightness(const xr::DisplayFrame& frame) {
  const render::Image& image = frame.read_back[0];
  Eigen::Vector2f low, high;
  EXPECT_TRUE(render::project_to_pixel(frame.cameras[0], image.width, image.height,
                                       {-0.15f, 0.10f, -0.25f}, &low));
  EXPECT_TRUE(render::project_to_pixel(frame.cameras[0], image.width, image.height,
                                       {0.15f, 0.16f, -0.25f}, &high));
  double sum = 0.0;
  long n = 0;
  for (int y = int(high.y()); y <= int(low.y()); ++y)
    for (int x = int(low.x()); x <= int(high.x()); ++x, ++n) {
      const auto p = image.pixel(x, y);
      sum += (p[0] + p[1] + p[2]) / 3.0;
    }
  return n ? sum / double(n) : 0.0;
}

// Starts the session and waits for its first trial to end, the session holding after it,
// then stops it.
void run_one_trial(SessionPage* page) {
  QSignalSpy ended(page, &SessionPage::session_ended);
  ASSERT_EQ(page->start_session(), QString());
  ASSERT_TRUE(page->session_running());
  SessionWorker* worker = page->worker();
  QSignalSpy trial_ended(worker, &SessionWorker::trial_ended);
  // The panel's trial line, set (queued to this thread) when the first trial starts: a spy
  // made now could miss the worker's own signal.
  const QLabel* trial = page->findChild<QLabel*>("trial");
  ASSERT_TRUE(QTest::qWaitFor([trial] { return trial->text().startsWith("1 of"); }, 60000))
      << session_log(*page).toStdString();
  page->toggle_pause();  // the session holds after this, its first trial
  ASSERT_TRUE(trial_ended.count() > 0 || trial_ended.wait(60000))
      << session_log(*page).toStdString();
  page->stop_session();
  ASSERT_TRUE(ended.wait(30000)) << session_log(*page).toStdString();
}

TEST(AppHeadset, RunsATrialInTheHeadsetChosenInTheSessionPanel) {
  MainWindow window;
  SessionPage* page =
      headset_session(window, "app_headset", R"({"display": "headset", "tracker": "scripted"})");
  // The protocol's defaults chosen in the panel.
  EXPECT_EQ(page->display_box()->currentText(), "Headset (OpenXR)");
  EXPECT_EQ(page->tracker_box()->currentText(), "Scripted participant");
  // `handlab --list-xr` names the runtime and its headset, as the panel does.
  QProcess list;
  list.start(HANDLAB_APP, {"--list-xr"});
  ASSERT_TRUE(list.waitForFinished(30000));
  EXPECT_EQ(list.exitCode(), 0);
  const QString listed = QString::fromUtf8(list.readAllStandardOutput());
  EXPECT_TRUE(listed.contains("headset ") && listed.contains("XR_EXT_hand_tracking offered"))
      << listed.toStdString();
  // The panel names the runtime and its headset once the headset is chosen.
  const QString runtime = page->findChild<QLabel*>("openxr_state")->text();
  EXPECT_TRUE(runtime.contains("Simulated HMD")) << runtime.toStdString();
  EXPECT_FALSE(page->real_time_box()->isEnabled()) << "a headset's session runs in real time";

  // The questionnaire after the trial: the participant reads it on the headset's panel and
  // answers with the keys, once the headset shows it (within 10 s).
  double during_trial = -1.0, asked = -1.0;
  QObject::connect(page, &SessionPage::questionnaire_opened, [&](QuestionnaireForm* form) {
    during_trial = panel_lightness(*page->worker()->headset_frame());
    keep_eyes(*page->worker()->headset_frame(), "app-trial");
    QTimer::singleShot(0, [&, form] {
      (void)QTest::qWaitFor(  // judged below by `asked`
          [&] {
            asked = panel_lightness(*page->worker()->headset_frame());
            return asked > during_trial + 60.0;
          },
          10000);
      keep_eyes(*page->worker()->headset_frame(), "app-questionnaire");
      QTest::keyClick(form, Qt::Key_4);
      QTest::keyClick(form, Qt::Key_Return);
    });
  });
  run_one_trial(page);
  if (::testing::Test::HasFatalFailure()) return;
  SessionWorker* worker = page->worker();
  // The instruction's dark panel during the trial, the light form when asked.
  std::printf("headset panel: lightness %.0f in the trial, %.0f with the questionnaire\n",
              during_trial, asked);
  EXPECT_GE(during_trial, 0.0) << "the questionnaire was asked";
  EXPECT_LT(during_trial, 110.0);
  EXPECT_GT(asked, during_trial + 60.0);
  EXPECT_TRUE(session_log(*page).contains("questionnaire answered"));
  EXPECT_TRUE(session_log(*page).contains("Headset (OpenXR)"));

  // The headset showed the trial: every frame waited for, begun and ended once, each shown
  // frame read back from both swapchains as drawn, the cube at its pixel in most (the hand
  // covers it in some).
  const auto counts = worker->headset_counts();
  ASSERT_TRUE(counts.has_value());
  const xr::DisplayCounts& loop = counts->loop;
  std::printf(
      "headset: %ld frames waited, %ld shown, the cube seen in %ld (left) and %ld (right)\n",
      loop.waits, counts->shown, counts->cube_seen[0], counts->cube_seen[1]);
  EXPECT_EQ(loop.waits, loop.begins);
  EXPECT_EQ(loop.begins, loop.ends);
  EXPECT_GE(counts->shown, 10) << "a 2-second trial at the runtime's pace";
  EXPECT_EQ(counts->read_back_as_drawn, counts->shown);
  EXPECT_GE(counts->cube_seen[0], counts->shown / 2);
  EXPECT_GE(counts->cube_seen[1], counts->shown / 2);
  const auto last = worker->headset_frame();
  ASSERT_TRUE(last.has_value());
  ASSERT_TRUE(last->drawn);
  EXPECT_NE(last->read_back[0].rgba, last->read_back[1].rgba) << "the two eyes see apart";
  keep_eyes(*last);
  // The experimenter's window shows the scene, and under it what the headset shows.
  EXPECT_NE(page->view()->frame(), nullptr);
  const auto* mirror = page->findChild<QLabel*>("headset_mirror");
  EXPECT_FALSE(mirror->isHidden());
  EXPECT_FALSE(mirror->pixmap().isNull());
  if (const char* dir = std::getenv("HANDLAB_HEADSET_SCREENSHOTS")) {
    window.tabs()->setCurrentWidget(page);
    window.grab().save(QString(dir) + "/app-window.png");
  }

  expect_first_trial_stored("app_headset", 100);  // a trial of at most 2 s at 120 Hz
}

// The runtime's hands as the tracker, in the headset: the open palm calibrates, a trial runs
// on them and its frames are logged at 120 Hz. Needs a runtime that tracks hands and a hand
// held open before it: openxr-test.sh runs it on the remote driver (remote_hands.c, open).
TEST(AppHeadsetHands, CalibratesAndRunsATrialOnTheHeadsetsOwnHands) {
  MainWindow window;
  SessionPage* page = headset_session(window, "app_headset_hands", R"({"display": "window"})");
  page->tracker_box()->setCurrentIndex(page->tracker_box()->findText("OpenXR hands"));
  page->display_box()->setCurrentIndex(page->display_box()->findText("Headset (OpenXR)"));
  const QString runtime = page->findChild<QLabel*>("openxr_state")->text();
  EXPECT_TRUE(runtime.contains("tracks hands")) << runtime.toStdString();
  QObject::connect(page, &SessionPage::questionnaire_opened, [](QuestionnaireForm* form) {
    QTimer::singleShot(0, [form] {
      QTest::keyClick(form, Qt::Key_3);
      QTest::keyClick(form, Qt::Key_Return);
    });
  });
  run_one_trial(page);
  if (::testing::Test::HasFatalFailure()) return;
  const QString log = session_log(*page);
  EXPECT_TRUE(log.contains("OpenXR hands")) << log.toStdString();
  EXPECT_TRUE(page->calibration_label()->text().startsWith("Calibrated: scale"))
      << page->calibration_label()->text().toStdString();
  const auto counts = page->worker()->headset_counts();
  ASSERT_TRUE(counts.has_value());
  EXPECT_GE(counts->shown, 10);
  // The trial's frames (2 s at the runtime's 20 Hz), not the calibration's or the
  // questionnaire's, show scenes made from new hand frames.
  EXPECT_GE(counts->latency_ms.size(), 20u)
      << "the time from each hand frame to the headset showing it";
  std::vector<double> latency = counts->latency_ms;
  std::sort(latency.begin(), latency.end());
  if (!latency.empty())
    std::printf(
        "headset: %ld frames shown; hand to headset %zu times, %.1f ms median, %.1f ms "
        "max\n",
        counts->shown, latency.size(), latency[latency.size() / 2], latency.back());
  keep_eyes(*page->worker()->headset_frame());
  expect_first_trial_stored("app_headset_hands", 230);
}

}  // namespace
}  // namespace handlab::gui
