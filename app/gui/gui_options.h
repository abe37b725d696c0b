// The app's command line: each option declared once (name, value, help, default) on a
// QCommandLineParser, and what the options ask for read and checked once, before any window
// is made.
#pragma once

#include <optional>
#include <stdexcept>

#include <QCommandLineParser>
#include <QString>

namespace handlab::gui {

// An option out of its range: one line, the app exits with status 2.
struct GuiUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct GuiOptions {
  QString study;        // the study database to open (empty: none)
  QString tab;          // study, participants, session or analysis (empty: as opened)
  QString participant;  // selected; with start, whose session runs
  bool participant_window = false;
  int replay = 0;  // the participant's trial to play back, 1-based (0: none)
  // A session started once shown.
  bool start = false;
  QString tracker;  // leap, openxr, scripted, simulated or a recording file (empty: as set up)
  bool proxy_world = false;     // the grasp proxy instead of the soft hand
  std::optional<bool> headset;  // the participant in the OpenXR headset (none: as set up)
  QString leap_address;
  bool real_time = true;
  double measure_latency = 0.0;  // s of the display's latency measured (0: none)
  QString latency_json;
  // The scripted pinch in the view.
  double pinch = 0.0;        // the cube's side, m (0: none)
  double pinch_until = 0.0;  // s (0: the script's end)
  bool contacts = false;
  // A screenshot, then quit.
  QString screenshot;
  bool screenshot_at_questionnaire = false;
  std::optional<double> screenshot_seconds;  // after the window shows (none: the default)
  // No window: a recording served over the Leap protocol.
  QString serve_recording;
  int port = 6437;
};

// Declares the options on `parser`, with --help and --version.
void add_gui_options(QCommandLineParser& parser);

// What `parser` read (after process()), checked: GuiUsageError for an option out of range.
GuiOptions read_gui_options(const QCommandLineParser& parser);

}  // namespace handlab::gui
