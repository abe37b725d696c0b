#include "app/gui/gui_options.h"

#include <cmath>

namespace handlab::gui {
namespace {

double number(const QCommandLineParser& parser, const char* name, bool& ok) {
  return parser.value(name).toDouble(&ok);
}

}  // namespace

void add_gui_options(QCommandLineParser& parser) {
  parser.setApplicationDescription(
      "Runs and analyses studies of fine virtual manipulation: create a study from a "
      "protocol, enrol participants, run their sessions with a live Leap Motion, a "
      "recording or a simulated participant on the soft hand, and analyse the results.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addOptions({
      {"study", "Open a study database.", "DB"},
      {"screenshot", "Save the window as PNG once shown, then quit.", "PNG"},
      {"tab", "Show this screen first: study, participants, session, analysis.", "SCREEN"},
      {"pinch", "Simulate the scripted pinch-and-lift of a cube of this side (m) in the view.",
       "METRES"},
      {"pinch-until", "Stop the simulated pinch at this time (s); with --screenshot, save then.",
       "SECONDS"},
      {"contacts", "Show the simulation's contact points."},
      {"participant", "The participant selected (with --start: whose session runs).", "ID"},
      {"tracker",
       "With --start: leap, openxr, scripted, simulated or a recording file (default: the "
       "protocol's session tracker, else scripted).",
       "TRACKER"},
      // Not --display: Qt takes that (and -display) as the X server to use.
      {"participant-view",
       "With --start: where the participant looks: window or headset (OpenXR) (default: the "
       "protocol's session display, else window).",
       "VIEW", "window"},
      {"list-xr",
       "No window: say which OpenXR runtime, headset and hand tracking are found, then quit."},
      {"world", "With --start: soft (the soft hand) or proxy.", "WORLD", "soft"},
      {"start", "Start (or resume) the participant's session once shown."},
      {"participant-window", "Show the participant's window (in a window)."},
      {"leap-address", "With --tracker leap: the Leap service's WebSocket address.", "URL",
       "ws://127.0.0.1:6437"},
      {"measure-latency",
       "With --start: after the first trial's 3 s warm-up, measure the display's latency, "
       "dropped frames and rate for this long, stop the session, write --latency-json, quit.",
       "SECONDS"},
      {"latency-json", "Where --measure-latency writes its figures.", "OUT"},
      {"serve-recording",
       "No window: serve this recording as the Leap service would (WebSocket JSON v6 on "
       "loopback, --port), at its own frame rate, looped, until interrupted.",
       "FILE"},
      {"port", "With --serve-recording: the port.", "PORT", "6437"},
      {"screenshot-at",
       "With --screenshot: when to save, in seconds after the window shows (default 1.5; "
       "6 with --start), or 'questionnaire' (when the first questionnaire opens; the dialog "
       "is drawn over the window where it stands).",
       "WHEN"},
      {"no-real-time",
       "With --start and a scripted or simulated participant or a recording: run as fast as "
       "the pipeline goes."},
      {"replay",
       "With --participant: play their trial N (1-based, as the schedule shows it) back from "
       "the study's frame log.",
       "N"},
  });
}

GuiOptions read_gui_options(const QCommandLineParser& parser) {
  GuiOptions o;
  o.study = parser.value("study");
  o.tab = parser.value("tab");
  if (!o.tab.isEmpty() &&
      !QStringList{"study", "participants", "session", "analysis"}.contains(o.tab))
    throw GuiUsageError("--tab is study, participants, session or analysis");
  o.participant = parser.value("participant");
  o.participant_window = parser.isSet("participant-window");
  if (parser.isSet("replay")) {
    bool ok = false;
    o.replay = parser.value("replay").toInt(&ok);
    if (!ok || o.replay < 1 || o.participant.isEmpty())
      throw GuiUsageError("--replay takes a trial number from 1 and --participant");
  }
  o.start = parser.isSet("start");
  if (parser.isSet("tracker")) o.tracker = parser.value("tracker");
  o.proxy_world = parser.value("world") == "proxy";
  const QString view = parser.value("participant-view");
  if (view != "window" && view != "headset")
    throw GuiUsageError("--participant-view is window or headset");
  if (parser.isSet("participant-view")) o.headset = view == "headset";
  o.leap_address = parser.value("leap-address");
  o.real_time = !parser.isSet("no-real-time");
  if (o.start && parser.isSet("measure-latency")) {
    bool ok = false;
    o.measure_latency = number(parser, "measure-latency", ok);
    o.latency_json = parser.value("latency-json");
    if (!ok || !std::isfinite(o.measure_latency) || !(o.measure_latency > 0) ||
        o.latency_json.isEmpty())
      throw GuiUsageError("--measure-latency takes seconds and --latency-json");
  }
  if (parser.isSet("pinch")) {
    bool ok = false, until_ok = true;
    o.pinch = number(parser, "pinch", ok);
    if (parser.isSet("pinch-until")) o.pinch_until = number(parser, "pinch-until", until_ok);
    if (!ok || !(o.pinch >= 0.005 && o.pinch <= 0.1) || !until_ok || o.pinch_until < 0)
      throw GuiUsageError(
          "--pinch takes a cube side of 0.005 to 0.1 m and --pinch-until a time in seconds");
    o.contacts = parser.isSet("contacts");
  }
  o.screenshot = parser.value("screenshot");
  const QString when = parser.value("screenshot-at");
  if (!o.screenshot.isEmpty() && !when.isEmpty()) {
    bool ok = false;
    o.screenshot_at_questionnaire = when == "questionnaire";
    if (!o.screenshot_at_questionnaire) o.screenshot_seconds = when.toDouble(&ok);
    if (!o.screenshot_at_questionnaire &&
        (!ok || !std::isfinite(*o.screenshot_seconds) || *o.screenshot_seconds < 0))
      throw GuiUsageError("--screenshot-at takes seconds or 'questionnaire'");
  }
  o.serve_recording = parser.value("serve-recording");
  bool port_ok = false;
  o.port = parser.value("port").toInt(&port_ok);
  if (!o.serve_recording.isEmpty() && (!port_ok || o.port < 0 || o.port > 65535))
    throw GuiUsageError("--port takes 0 to 65535");
  return o;
}

}  // namespace handlab::gui
