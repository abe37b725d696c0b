// handlab: the desktop application.
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>

#include <cstdio>
#include <optional>
#include <string>

#include "app/gui/gui_options.h"
#include "app/gui/main_window.h"
#include "app/gui/startup.h"
#include "app/live/leap_replay_server.h"
#include "core/tracking/recording_io.h"
#include "core/util/build_info.h"
#include "core/xr/openxr_runtime.h"

namespace {

using handlab::gui::GuiOptions;

void name_application() {
  QCoreApplication::setApplicationName("handlab");
  QCoreApplication::setOrganizationName("handlab");
  QCoreApplication::setApplicationVersion(QString::fromStdString(handlab::util::version_line()));
}

// The command line processed (--help and --version print and exit) and checked; nothing when an
// option is out of range (said on stderr).
std::optional<GuiOptions> read_command_line(QCoreApplication& app) {
  QCommandLineParser parser;
  handlab::gui::add_gui_options(parser);
  parser.process(app);
  try {
    return handlab::gui::read_gui_options(parser);
  } catch (const handlab::gui::GuiUsageError& e) {
    std::fprintf(stderr, "handlab: %s\n", e.what());
    return std::nullopt;
  }
}

bool asks(int argc, char** argv, bool (*what)(const std::string&)) {
  for (int k = 1; k < argc; ++k)
    if (what(argv[k])) return true;
  return false;
}

// A recording served over the Leap protocol, with no window (and no display needed).
int serve_recording(int argc, char** argv) {
  QCoreApplication core(argc, argv);
  name_application();
  const std::optional<GuiOptions> options = read_command_line(core);
  if (!options) return 2;
  try {
    handlab::tracking::Recording recording =
        handlab::tracking::read_recording(options->serve_recording.toStdString());
    handlab::live::LeapReplayServer server(std::move(recording.frames),
                                           {quint16(options->port), /*loop=*/true});
    QString error;
    if (!server.start(&error)) {
      std::fprintf(stderr, "handlab: cannot listen on port %d: %s\n", options->port,
                   qPrintable(error));
      return 1;
    }
    std::printf("serving %s at %.1f frames/s on ws://127.0.0.1:%d/v6.json\n",
                qPrintable(options->serve_recording), server.frame_rate_hz(), int(server.port()));
    std::fflush(stdout);
    return core.exec();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "handlab: %s\n", e.what());
    return 1;
  }
}

// The OpenXR runtime's offer, with no window: as `handlab-cli xr list` says it.
int list_xr() {
  const handlab::xr::OpenXrRuntimeInfo info = handlab::xr::probe_openxr_runtime();
  if (!info.found) {
    std::fprintf(stderr, "handlab: %s (docs/hmd.md says how to start one)\n", info.error.c_str());
    return 1;
  }
  std::fputs(handlab::xr::runtime_description(info).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // --help and --version answer without a display: no GUI application is made for them.
  if (asks(argc, argv, [](const std::string& a) {
        return a == "-h" || a == "--help" || a == "--help-all" || a == "-v" || a == "--version";
      })) {
    QCoreApplication core(argc, argv);
    name_application();
    read_command_line(core);  // prints and exits
    return 0;
  }
  if (asks(argc, argv, [](const std::string& a) { return a == "--list-xr"; })) return list_xr();
  if (asks(argc, argv, [](const std::string& a) { return a.rfind("--serve-recording", 0) == 0; }))
    return serve_recording(argc, argv);
  // The renderer speaks OpenGL 3.3 core; the format must be set before the application.
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  name_application();
  const std::optional<GuiOptions> options = read_command_line(app);
  if (!options) return 2;
  handlab::gui::MainWindow window;
  window.show();
  if (const auto status = handlab::gui::start_up(window, *options, app)) return *status;
  return app.exec();
}
