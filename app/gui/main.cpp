// handlab: the desktop application.
#include <QApplication>
#include <QSurfaceFormat>

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
  handlab::gui::MainWindow window;
  window.show();
  return app.exec();
}
