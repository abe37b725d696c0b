#include "app/cli/gui_application.h"

#include <iostream>

#include <QGuiApplication>

namespace handlab::cli {

void ensure_gui_application() {
  if (QCoreApplication::instance()) return;
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  static int argc = 1;
  static char name[] = "handlab-cli";
  static char* argv[] = {name, nullptr};
  // Qt's note that XDG_RUNTIME_DIR is unset is noise for a command-line job.
  qInstallMessageHandler([](QtMsgType type, const QMessageLogContext&, const QString& message) {
    if (message.contains("XDG_RUNTIME_DIR")) return;
    std::cerr << (type == QtWarningMsg ? "warning: " : "") << message.toStdString() << "\n";
  });
  static QGuiApplication app(argc, argv);
}

}  // namespace handlab::cli
