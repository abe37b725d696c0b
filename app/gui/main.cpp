// handlab: the desktop application.
#include <QApplication>
#include <QCommandLineParser>
#include <QMessageBox>
#include <QSurfaceFormat>
#include <QTimer>

#include <cstdio>

#include "app/gui/main_window.h"
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
  parser.addOption(study);
  parser.addOption(screenshot);
  parser.process(app);

  handlab::gui::MainWindow window;
  window.show();
  if (parser.isSet(study)) {
    const QString error = window.show_study(parser.value(study));
    if (!error.isEmpty()) QMessageBox::warning(&window, "handlab", error);
  }
  if (parser.isSet(screenshot)) {
    QTimer::singleShot(1500, &window, [&] {
      const bool saved = window.grab().save(parser.value(screenshot));
      if (!saved)
        std::fprintf(stderr, "handlab: cannot write %s\n", qPrintable(parser.value(screenshot)));
      app.exit(saved ? 0 : 1);
    });
  }
  return app.exec();
}
