// handlab: the desktop application.
#include <QApplication>
#include <QComboBox>
#include <QCommandLineParser>
#include <QLineEdit>
#include <QMessageBox>
#include <QRegularExpression>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTimer>

#include <cstdio>
#include <string>

#include "app/gui/analysis_page.h"
#include "app/gui/main_window.h"
#include "app/gui/participant_window.h"
#include "app/gui/participants_page.h"
#include "app/gui/pinch_simulation.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_page.h"
#include "app/gui/study_home.h"
#include "handlab/version.h"

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
  QCommandLineOption participant{"participant", "With --start: the participant whose session runs.",
                                 "ID"};
  QCommandLineOption tracker{"tracker",
                             "With --start: leap, scripted, simulated or a recording file.",
                             "TRACKER", "scripted"};
  QCommandLineOption world{"world", "With --start: soft (the soft hand) or proxy.", "WORLD",
                           "soft"};
  QCommandLineOption start{"start", "Start (or resume) the participant's session once shown."};
  QCommandLineOption participant_window{"participant-window",
                                        "Show the participant's window (in a window)."};

  void add_to(QCommandLineParser& parser) {
    parser.setApplicationDescription(
        "Runs and analyses studies of fine virtual manipulation: create a study from a "
        "protocol, enrol participants, run their sessions with a live Leap Motion, a "
        "recording or a simulated participant on the soft hand, and analyse the results.");
    parser.addHelpOption();
    parser.addVersionOption();
    for (const auto* o : {&study, &screenshot, &tab, &pinch, &pinch_until, &contacts, &participant,
                          &tracker, &world, &start, &participant_window})
      parser.addOption(*o);
  }
};

}  // namespace

int main(int argc, char** argv) {
  // --help and --version answer without a display: no GUI application is made for them.
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "-h" || arg == "--help" || arg == "--help-all" || arg == "-v" ||
        arg == "--version") {
      QCoreApplication core(argc, argv);
      QCoreApplication::setApplicationName("handlab");
      QCoreApplication::setApplicationVersion(HANDLAB_VERSION);
      QCommandLineParser parser;
      Options options;
      options.add_to(parser);
      parser.process(core);  // prints and exits
      return 0;
    }
  }
  // The renderer speaks OpenGL 3.3 core; the format must be set before the application.
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setSamples(4);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  QApplication::setApplicationName("handlab");
  QApplication::setOrganizationName("handlab");
  QApplication::setApplicationVersion(HANDLAB_VERSION);
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
  if (parser.isSet(options.participant_window)) window.show_participant_window(-1);
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
      bool saved = window.grab().save(parser.value(screenshot));
      if (window.participant_window()) {  // beside it: NAME-participant.png
        QString path = parser.value(screenshot);
        path.replace(QRegularExpression("\\.png$"), "");
        saved = saved && window.participant_window()->grab().save(path + "-participant.png");
      }
      if (!saved)
        std::fprintf(stderr, "handlab: cannot write %s\n", qPrintable(parser.value(screenshot)));
      app.exit(saved ? 0 : 1);
    };
    if (simulation)  // once the simulation has reached its end and the view shows it
      QObject::connect(simulation, &handlab::gui::PinchSimulation::done, &window,
                       [&] { QTimer::singleShot(500, &window, save); });
    else
      QTimer::singleShot(parser.isSet(options.start) ? 6000 : 1500, &window, save);
  }
  return app.exec();
}
