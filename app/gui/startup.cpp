#include "app/gui/startup.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QLineEdit>
#include <QMessageBox>
#include <QPainter>
#include <QRegularExpression>
#include <QTabWidget>
#include <QTimer>

#include <cstdio>

#include "app/gui/analysis_page.h"
#include "app/gui/live_measurement.h"
#include "app/gui/main_window.h"
#include "app/gui/participant_window.h"
#include "app/gui/participants_page.h"
#include "app/gui/pinch_simulation.h"
#include "app/gui/questionnaire_form.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_page.h"
#include "app/gui/study_home.h"
#include "app/report/figure_file.h"

namespace handlab::gui {
namespace {

int failed(const QString& error) {
  std::fprintf(stderr, "handlab: %s\n", qPrintable(error));
  return 1;
}

// The study, the screen, the participant, the participant's window, a replay.
std::optional<int> show(MainWindow& window, const GuiOptions& o) {
  if (!o.study.isEmpty()) {
    const QString error = window.show_study(o.study);
    if (!error.isEmpty()) QMessageBox::warning(&window, "handlab", error);
  }
  if (!o.tab.isEmpty()) {
    QWidget* pages[] = {window.home(), window.participants(), window.session(), window.analysis()};
    const QStringList names = {"study", "participants", "session", "analysis"};
    window.tabs()->setCurrentWidget(pages[names.indexOf(o.tab)]);
  }
  if (!o.participant.isEmpty() && !o.start) window.participants()->select(o.participant);
  if (o.participant_window) window.show_participant_window(-1);
  if (o.replay > 0) {
    const QString error = window.session()->replay_trial(o.participant, o.replay - 1);
    if (!error.isEmpty()) return failed(error);
    window.tabs()->setCurrentWidget(window.session());
  }
  return std::nullopt;
}

// The participant's session, with the tracker and world asked for; its latency measured.
std::optional<int> start_session(MainWindow& window, const GuiOptions& o, QApplication& app) {
  SessionPage* page = window.session();
  page->participant_box()->setCurrentText(o.participant);
  // Where nothing is asked for, the protocol's session defaults, else the scripted participant.
  const bool named = page->protocol() && !page->protocol()->default_tracker.empty();
  const QString tracker = !o.tracker.isEmpty() ? o.tracker : named ? QString() : "scripted";
  if (!tracker.isEmpty()) {
    const int choice = tracker == "leap"        ? 0
                       : tracker == "simulated" ? 2
                       : tracker == "scripted"  ? 3
                       : tracker == "openxr"    ? 4
                                                : 1;
    page->tracker_box()->setCurrentIndex(choice);
    if (choice == 1) page->recording_edit()->setText(tracker);
  }
  if (o.headset) page->display_box()->setCurrentIndex(*o.headset ? 1 : 0);
  page->world_box()->setCurrentIndex(o.proxy_world ? 1 : 0);
  page->set_leap_address(o.leap_address);
  page->real_time_box()->setChecked(o.real_time);
  if (o.measure_latency > 0) {
    auto* measurement = new LiveMeasurement(page, o.measure_latency, o.latency_json, &window);
    QObject::connect(measurement, &LiveMeasurement::done, &app, [&app](bool ok) {
      if (!ok) std::fprintf(stderr, "handlab: the latency was not measured\n");
      app.exit(ok ? 0 : 1);
    });
  }
  window.tabs()->setCurrentWidget(page);
  const QString error = page->start_session();
  if (!error.isEmpty()) return failed(error);
  return std::nullopt;
}

PinchSimulation* start_pinch(MainWindow& window, const GuiOptions& o) {
  task::SceneLayout layout = window.scene_view()->layout();
  layout.cube_size = o.pinch;
  window.scene_view()->set_layout(layout);
  window.set_show_contacts(o.contacts);
  return window.start_pinch(o.pinch_until);
}

// The window (with a questionnaire dialog over it, where it stands) and the participant's
// window beside it (NAME-participant.png); the app quits.
void save_screenshot(MainWindow& window, const QString& path, QApplication& app) {
  QImage picture = grab_with_views(&window);
  auto* form = window.session()->questionnaire();
  if (form && form->window() != window.participant_window()) {
    QWidget* dialog = form->window();
    QPainter painter(&picture);
    painter.drawPixmap(dialog->frameGeometry().topLeft() - window.frameGeometry().topLeft(),
                       dialog->grab());
  }
  bool saved = true;
  try {
    report::write_png_file(path.toStdString(), picture);
    if (window.participant_window()) {
      QString beside = path;
      beside.replace(QRegularExpression("\\.png$"), "");
      report::write_png_file((beside + "-participant.png").toStdString(),
                             grab_with_views(window.participant_window()));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "handlab: %s\n", e.what());
    saved = false;
  }
  app.exit(saved ? 0 : 1);
}

// Once the pinch has reached its end, the first questionnaire opens, or the seconds passed.
void schedule_screenshot(MainWindow& window, const GuiOptions& o, PinchSimulation* simulation,
                         QApplication& app) {
  MainWindow* shown = &window;
  const QString path = o.screenshot;
  auto save = [shown, path, &app] { save_screenshot(*shown, path, app); };
  auto soon = [shown, save] { QTimer::singleShot(500, shown, save); };
  if (simulation)
    QObject::connect(simulation, &PinchSimulation::done, &window, soon);
  else if (o.screenshot_at_questionnaire)
    QObject::connect(window.session(), &SessionPage::questionnaire_opened, &window, soon);
  else
    QTimer::singleShot(int(o.screenshot_seconds.value_or(o.start ? 6.0 : 1.5) * 1000), &window,
                       save);
}

}  // namespace

std::optional<int> start_up(MainWindow& window, const GuiOptions& options, QApplication& app) {
  if (const auto status = show(window, options)) return status;
  if (options.start)
    if (const auto status = start_session(window, options, app)) return status;
  PinchSimulation* simulation = options.pinch > 0 ? start_pinch(window, options) : nullptr;
  if (!options.screenshot.isEmpty()) schedule_screenshot(window, options, simulation, app);
  return std::nullopt;
}

}  // namespace handlab::gui
