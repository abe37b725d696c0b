// handlab: the desktop application.
#include <QApplication>
#include <QCommandLineParser>
#include <QMessageBox>
#include <QSurfaceFormat>
#include <QTimer>

#include <cstdio>

#include "app/gui/main_window.h"
#include "app/gui/pinch_simulation.h"
#include "app/gui/scene_view.h"
#include "handlab/version.h"

int main(int argc, char** argv) {
  // The renderer speaks OpenGL 3.3 core; the format must be set before the application.
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setSamples(4);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  QApplication::setApplicationName("handlab");
  QApplication::setApplicationVersion(HANDLAB_VERSION);
  QCommandLineParser parser;
  parser.setApplicationDescription("Runs and analyses studies of fine virtual manipulation.");
  parser.addHelpOption();
  parser.addVersionOption();
  const QCommandLineOption study("study", "Open a study database's progress panel.", "DB");
  const QCommandLineOption screenshot("screenshot", "Save the window as PNG once shown, then quit.",
                                      "PNG");
  const QCommandLineOption pinch(
      "pinch", "Simulate the scripted pinch-and-lift of a cube of this side (m) in the view.",
      "METRES");
  const QCommandLineOption pinch_until(
      "pinch-until", "Stop the simulated pinch at this time (s); with --screenshot, save then.",
      "SECONDS");
  const QCommandLineOption contacts("contacts", "Show the simulation's contact points.");
  parser.addOption(study);
  parser.addOption(screenshot);
  parser.addOption(pinch);
  parser.addOption(pinch_until);
  parser.addOption(contacts);
  parser.process(app);

  handlab::gui::MainWindow window;
  window.show();
  if (parser.isSet(study)) {
    const QString error = window.show_study(parser.value(study));
    if (!error.isEmpty()) QMessageBox::warning(&window, "handlab", error);
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
      const bool saved = window.grab().save(parser.value(screenshot));
      if (!saved)
        std::fprintf(stderr, "handlab: cannot write %s\n", qPrintable(parser.value(screenshot)));
      app.exit(saved ? 0 : 1);
    };
    if (simulation)  // once the simulation has reached its end and the view shows it
      QObject::connect(simulation, &handlab::gui::PinchSimulation::done, &window,
                       [&] { QTimer::singleShot(500, &window, save); });
    else
      QTimer::singleShot(1500, &window, save);
  }
  return app.exec();
}
