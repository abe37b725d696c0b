// handlab: the desktop application.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QCommandLineParser>
#include <QLineEdit>
#include <QMessageBox>
#include <QPainter>
#include <QRegularExpression>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTimer>

#include <cstdio>
#include <string>

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
#include "app/live/leap_replay_server.h"
#include "app/report/figure_file.h"
#include "core/tracking/recording_io.h"
#include "core/util/build_info.h"

namespace {

struct Options {
  QCommandLineOption study{"study", "Open a study database.", "DB"};
  QCommandLineOption screenshot{"screenshot", "Save the window as PNG once shown, then quit.",
                                "PNG"};
  QCommandLineOption tab{"tab", "Show this screen first: study, participants, session, analysis.",
                         "SCREEN"};
  QCommandLineOption pinch{
      "pinch", "Simulate the scripted pinch-and-lift of a cube of this side (m) in the view.",
      "METRES"};
  QCommandLineOption pinch_until{
      "pinch-until", "Stop the simulated pinch at this time (s); with --screenshot, save then.",
      "SECONDS"};
  QCommandLineOption contacts{"contacts", "Show the simulation's contact points."};
  QCommandLineOption participant{
      "participant", "The participant selected (with --start: whose session runs).", "ID"};
  QCommandLineOption tracker{"tracker",
                             "With --start: leap, scripted, simulated or a recording file.",
                             "TRACKER", "scripted"};
  QCommandLineOption world{"world", "With --start: soft (the soft hand) or proxy.", "WORLD",
                           "soft"};
  QCommandLineOption start{"start", "Start (or resume) the participant's session once shown."};
  QCommandLineOption participant_window{"participant-window",
                                        "Show the participant's window (in a window)."};
  QCommandLineOption leap_address{"leap-address",
                                  "With --tracker leap: the Leap service's WebSocket address.",
                                  "URL", "ws://127.0.0.1:6437"};
  QCommandLineOption measure_latency{
      "measure-latency",
      "With --start: after the first trial's 3 s warm-up, measure the display's latency, "
      "dropped frames and rate for this long, stop the session, write --latency-json, quit.",
      "SECONDS"};
  QCommandLineOption latency_json{"latency-json", "Where --measure-latency writes its figures.",
                                  "OUT"};
  QCommandLineOption serve_recording{
      "serve-recording",
      "No window: serve this recording as the Leap service would (WebSocket JSON v6 on "
      "loopback, --port), at its own frame rate, looped, until interrupted.",
      "FILE"};
  QCommandLineOption port{"port", "With --serve-recording: the port.", "PORT", "6437"};
  QCommandLineOption screenshot_at{
      "screenshot-at",
      "With --screenshot: when to save, in seconds after the window shows (default 1.5; "
      "6 with --start), or 'questionnaire' (when the first questionnaire opens; the dialog "
      "is drawn over the window where it stands).",
      "WHEN"};
  QCommandLineOption replay{"replay",
                            "With --participant: play their trial N (1-based, as the schedule "
                            "shows it) back from the study's frame log.",
                            "N"};
  QCommandLineOption no_real_time{"no-real-time",
                                  "With --start and a scripted or simulated participant or a "
                                  "recording: run as fast as the pipeline goes."};

  void add_to(QCommandLineParser& parser) {
    parser.setApplicationDescription(
        "Runs and analyses studies of fine virtual manipulation: create a study from a "
        "protocol, enrol participants, run their sessions with a live Leap Motion, a "
        "recording or a simulated participant on the soft hand, and analyse the results.");
    parser.addHelpOption();
    parser.addVersionOption();
    for (const auto* o :
         {&study, &screenshot, &tab, &pinch, &pinch_until, &contacts, &participant, &tracker,
          &world, &start, &participant_window, &leap_address, &measure_latency, &latency_json,
          &serve_recording, &port, &screenshot_at, &no_real_time, &replay})
      parser.addOption(*o);
  }
};

// The command line read by an application made without a display.
void process_without_display(QCoreApplication& core, QCommandLineParser& parser, Options& options) {
  QCoreApplication::setApplicationName("handlab");
  QCoreApplication::setApplicationVersion(QString::fromStdString(handlab::util::version_line()));
  options.add_to(parser);
  parser.process(core);
}

// A recording served over the Leap protocol, with no window (and no display needed).
int serve_recording(int argc, char** argv) {
  QCoreApplication core(argc, argv);
  QCommandLineParser parser;
  Options options;
  process_without_display(core, parser, options);
  bool ok = false;
  const int port = parser.value(options.port).toInt(&ok);
  if (!ok || port < 0 || port > 65535) {
    std::fprintf(stderr, "handlab: --port takes 0 to 65535\n");
    return 2;
  }
  try {
    handlab::tracking::Recording recording =
        handlab::tracking::read_recording(parser.value(options.serve_recording).toStdString());
    handlab::live::LeapReplayServer server(std::move(recording.frames),
                                           {quint16(port), /*loop=*/true});
    QString error;
    if (!server.start(&error)) {
      std::fprintf(stderr, "handlab: cannot listen on port %d: %s\n", port, qPrintable(error));
      return 1;
    }
    std::printf("serving %s at %.1f frames/s on ws://127.0.0.1:%d/v6.json\n",
                qPrintable(parser.value(options.serve_recording)), server.frame_rate_hz(),
                int(server.port()));
    std::fflush(stdout);
    return core.exec();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "handlab: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // --help and --version answer without a display: no GUI application is made for them.
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "-h" || arg == "--help" || arg == "--help-all" || arg == "-v" ||
        arg == "--version") {
      QCoreApplication core(argc, argv);
      QCommandLineParser parser;
      Options options;
      process_without_display(core, parser, options);  // prints and exits
      return 0;
    }
  }
  for (int k = 1; k < argc; ++k)
    if (std::string(argv[k]).rfind("--serve-recording", 0) == 0) return serve_recording(argc, argv);
  // The renderer speaks OpenGL 3.3 core; the format must be set before the application.
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  QApplication::setApplicationName("handlab");
  QApplication::setOrganizationName("handlab");
  QApplication::setApplicationVersion(QString::fromStdString(handlab::util::version_line()));
  QCommandLineParser parser;
  Options options;
  options.add_to(parser);
  parser.process(app);
  const auto& study = options.study;
  const auto& screenshot = options.screenshot;
  const auto& pinch = options.pinch;
  const auto& pinch_until = options.pinch_until;
  const auto& contacts = options.contacts;

  handlab::gui::MainWindow window;
  window.show();
  if (parser.isSet(study)) {
    const QString error = window.show_study(parser.value(study));
    if (!error.isEmpty()) QMessageBox::warning(&window, "handlab", error);
  }
  if (parser.isSet(options.tab)) {
    const QString name = parser.value(options.tab);
    QWidget* pages[] = {window.home(), window.participants(), window.session(), window.analysis()};
    const QStringList names = {"study", "participants", "session", "analysis"};
    if (!names.contains(name)) {
      std::fprintf(stderr, "handlab: --tab is study, participants, session or analysis\n");
      return 2;
    }
    window.tabs()->setCurrentWidget(pages[names.indexOf(name)]);
  }
  if (parser.isSet(options.participant) && !parser.isSet(options.start))
    window.participants()->select(parser.value(options.participant));
  if (parser.isSet(options.participant_window)) window.show_participant_window(-1);
  if (parser.isSet(options.replay)) {
    bool ok = false;
    const int trial = parser.value(options.replay).toInt(&ok);
    if (!ok || trial < 1 || !parser.isSet(options.participant)) {
      std::fprintf(stderr, "handlab: --replay takes a trial number from 1 and --participant\n");
      return 2;
    }
    const QString error =
        window.session()->replay_trial(parser.value(options.participant), trial - 1);
    if (!error.isEmpty()) {
      std::fprintf(stderr, "handlab: %s\n", qPrintable(error));
      return 1;
    }
    window.tabs()->setCurrentWidget(window.session());
  }
  if (parser.isSet(options.start)) {
    handlab::gui::SessionPage* page = window.session();
    page->participant_box()->setCurrentText(parser.value(options.participant));
    const QString tracker = parser.value(options.tracker);
    const int choice = tracker == "leap"        ? 0
                       : tracker == "simulated" ? 2
                       : tracker == "scripted"  ? 3
                                                : 1;
    page->tracker_box()->setCurrentIndex(choice);
    if (choice == 1) page->recording_edit()->setText(tracker);
    page->world_box()->setCurrentIndex(parser.value(options.world) == "proxy" ? 1 : 0);
    page->set_leap_address(parser.value(options.leap_address));
    page->real_time_box()->setChecked(!parser.isSet(options.no_real_time));
    if (parser.isSet(options.measure_latency)) {
      bool ok = false;
      const double seconds = parser.value(options.measure_latency).toDouble(&ok);
      if (!ok || !(seconds > 0) || !parser.isSet(options.latency_json)) {
        std::fprintf(stderr, "handlab: --measure-latency takes seconds and --latency-json\n");
        return 2;
      }
      auto* measurement = new handlab::gui::LiveMeasurement(
          page, seconds, parser.value(options.latency_json), &window);
      QObject::connect(measurement, &handlab::gui::LiveMeasurement::done, &app, [&](bool ok) {
        if (!ok) std::fprintf(stderr, "handlab: the latency was not measured\n");
        app.exit(ok ? 0 : 1);
      });
    }
    window.tabs()->setCurrentWidget(page);
    const QString error = page->start_session();
    if (!error.isEmpty()) {
      std::fprintf(stderr, "handlab: %s\n", qPrintable(error));
      return 1;
    }
  }
  handlab::gui::PinchSimulation* simulation = nullptr;
  if (parser.isSet(pinch)) {
    bool ok = false, until_ok = true;
    const double cube = parser.value(pinch).toDouble(&ok);
    const double until =
        parser.isSet(pinch_until) ? parser.value(pinch_until).toDouble(&until_ok) : 0.0;
    if (!ok || !(cube >= 0.005 && cube <= 0.1) || !until_ok || until < 0) {
      std::fprintf(stderr,
                   "handlab: --pinch takes a cube side of 0.005 to 0.1 m and "
                   "--pinch-until a time in seconds\n");
      return 2;
    }
    handlab::task::SceneLayout layout = window.scene_view()->layout();
    layout.cube_size = cube;
    window.scene_view()->set_layout(layout);
    window.set_show_contacts(parser.isSet(contacts));
    simulation = window.start_pinch(until);
  }
  if (parser.isSet(screenshot)) {
    auto save = [&] {
      QImage picture = handlab::gui::grab_with_views(&window);
      auto* form = window.session()->questionnaire();
      if (form && form->window() != window.participant_window()) {  // a dialog over the window
        QWidget* dialog = form->window();
        QPainter painter(&picture);
        painter.drawPixmap(dialog->frameGeometry().topLeft() - window.frameGeometry().topLeft(),
                           dialog->grab());
      }
      bool saved = true;
      try {
        handlab::report::write_png_file(parser.value(screenshot).toStdString(), picture);
        if (window.participant_window()) {  // beside it: NAME-participant.png
          QString path = parser.value(screenshot);
          path.replace(QRegularExpression("\\.png$"), "");
          handlab::report::write_png_file(
              (path + "-participant.png").toStdString(),
              handlab::gui::grab_with_views(window.participant_window()));
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "handlab: %s\n", e.what());
        saved = false;
      }
      app.exit(saved ? 0 : 1);
    };
    const QString when = parser.value(options.screenshot_at);
    bool seconds_ok = true;
    const double seconds =
        when.isEmpty() ? (parser.isSet(options.start) ? 6.0 : 1.5) : when.toDouble(&seconds_ok);
    if (simulation) {  // once the simulation has reached its end and the view shows it
      QObject::connect(simulation, &handlab::gui::PinchSimulation::done, &window,
                       [&] { QTimer::singleShot(500, &window, save); });
    } else if (when == "questionnaire") {
      QObject::connect(window.session(), &handlab::gui::SessionPage::questionnaire_opened, &window,
                       [&] { QTimer::singleShot(500, &window, save); });
    } else if (seconds_ok && seconds >= 0) {
      QTimer::singleShot(int(seconds * 1000), &window, save);
    } else {
      std::fprintf(stderr, "handlab: --screenshot-at takes seconds or 'questionnaire'\n");
      return 2;
    }
  }
  return app.exec();
}
