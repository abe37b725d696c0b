// handlab-cli session: run a participant's session headless; redo or skip a trial.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/nearest_word.h"
#include "app/cli/offscreen_eyes.h"
#include "app/cli/world_option.h"
#include "core/store/study_store.h"
#include "core/util/count_text.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "studies/protocol/protocol_store.h"
#include "studies/session/openxr_tracker.h"
#include "studies/session/session_control.h"
#include "studies/session/session_headset.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"

namespace handlab::cli {
namespace {

std::vector<OptionSpec> session_run_options() {
  return {
      {"db", "DB", "the study database"},
      {"participant", "ID", "an enrolled participant"},
      {"tracker", "scripted|simulated|openxr|FILE",
       "scripted: the built-in open-loop pick-and-place motion at the participant's hand size; "
       "simulated: the closed-loop participant model (docs/simulated-participants.md); openxr: "
       "the hands of the OpenXR runtime (XR_EXT_hand_tracking; in real time, calibrated with an "
       "open palm; docs/hmd.md); or a recording (.json, .json.lz, .hlrec) replayed for every "
       "trial (default: the protocol's \"session\" tracker, else scripted)",
       "scripted"},
      {"seed", "S", "with --tracker simulated: the population seed of the model's parameters", "0"},
      {"resume", "",
       "continue a started schedule (after a crash: the interrupted trial is "
       "kept as aborted and run again)"},
      world_option(),
      {"display", "none|headset",
       "headset: the participant's view in the OpenXR headset, the session in real time "
       "(docs/hmd.md) (default: the protocol's \"session\" display, else none)",
       "none"},
      {"quiet", "", "no line per trial"},
      {"json", "OUT", "write a summary as JSON (- for standard output)"},
  };
}

CommandHelp session_run_help() {
  return {"session run",
          {"db participant [tracker] [seed] [resume] [world] [display] [quiet] [json]"},
          "Runs the participant's schedule without the app: tracker -> retargeting -> hand-cube "
          "physics "
          "-> task, frames logged at 120 Hz, questionnaire where the protocol asks it (the "
          "scripted participant answers the middle of the scale)."};
}

// The time from a hand frame to the headset showing it: median, 95th percentile, largest.
struct LatencySummary {
  double median = 0.0, p95 = 0.0, max = 0.0;
};

LatencySummary summarise(std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  const auto at = [&](double q) { return ms[std::size_t(q * double(ms.size() - 1) + 0.5)]; };
  return {at(0.5), at(0.95), ms.back()};
}

void print_session_report(const std::string& participant, const studies::SessionReport& report,
                          double seconds, const std::optional<xr::HeadsetCounts>& shown) {
  if (report.aborted_before)
    std::cout << util::count_text(report.aborted_before, "interrupted trial")
              << " marked aborted, run again\n";
  if (report.stopped) std::cout << "the session stopped before its schedule's end\n";
  char duration[32];
  std::snprintf(duration, sizeof duration, "%.1f s", seconds);
  std::cout << participant << ": " << util::count_text(report.trials_run, "trial") << " run in "
            << duration << "; schedule " << (report.schedule_complete ? "complete" : "open")
            << "\n";
  if (!shown) return;
  std::cout << "headset: " << shown->shown << " frames shown, the cube at its pixel in "
            << shown->cube_seen[0] << " (left) and " << shown->cube_seen[1] << " (right)";
  if (!shown->latency_ms.empty()) {
    const LatencySummary l = summarise(shown->latency_ms);
    std::printf("; from hand to headset %.1f ms median, %.1f ms p95", l.median, l.p95);
    std::fflush(stdout);
  }
  std::cout << "\n";
}

void write_session_json(std::ostream& out, const std::string& participant,
                        const studies::SessionReport& report, double seconds,
                        const std::optional<xr::HeadsetCounts>& shown) {
  util::JsonWriter w(out);
  w.begin_object()
      .field("participant", participant)
      .field("trials_run", report.trials_run)
      .field("aborted_before", report.aborted_before)
      .field("schedule_complete", report.schedule_complete)
      .field("stopped", report.stopped)
      .field("seconds", seconds);
  if (shown) {
    w.key("headset")
        .begin_object()
        .field("frames_shown", int(shown->shown))
        .field("frames_waited", int(shown->loop.waits))
        .field("frames_begun", int(shown->loop.begins))
        .field("frames_ended", int(shown->loop.ends))
        .field("cube_seen_left", int(shown->cube_seen[0]))
        .field("cube_seen_right", int(shown->cube_seen[1]))
        .field("read_back_as_drawn", int(shown->read_back_as_drawn));
    if (!shown->latency_ms.empty()) {
      const LatencySummary l = summarise(shown->latency_ms);
      w.key("latency_ms")
          .begin_object()
          .field("samples", int(shown->latency_ms.size()))
          .field("median", l.median)
          .field("p95", l.p95)
          .field("max", l.max)
          .end_object();
    }
    w.end_object();
  }
  w.end_object();
  out << "\n";
}

// The participant's view in the headset, shown each step the session takes.
std::unique_ptr<studies::SessionHeadset> open_headset(studies::SessionControl& control,
                                                      const studies::Protocol& protocol,
                                                      std::function<void(const std::string&)> say,
                                                      bool hands) {
  auto headset = std::make_unique<studies::SessionHeadset>(control, protocol.scene,
                                                           offscreen_eyes(), std::move(say), hands);
  studies::SessionHeadset* h = headset.get();
  control.trial_started = [h](const studies::TrialSetup& s, int) { h->trial_started(s); };
  control.stepped = [h](const studies::TrialStep& step) { h->stepped(step); };
  return headset;
}

void check_tracker(const std::string& tracker) {
  if (tracker != "scripted" && tracker != "simulated" && tracker != "openxr" &&
      !std::filesystem::exists(tracker))
    throw UsageError("--tracker must be scripted, simulated, openxr or a recording file; '" +
                     tracker + "' is none of them" +
                     did_you_mean(tracker, {"scripted", "simulated", "openxr"}));
}

// The protocol's tracker ("session": {"tracker"}) where --tracker is not given.
std::string protocol_tracker(const studies::Protocol& protocol) {
  if (protocol.default_tracker == "leap")
    throw UsageError(
        "the protocol's session tracker is the Leap, which only the app reads live: give "
        "--tracker");
  return protocol.default_tracker.empty() ? "scripted" : protocol.default_tracker;
}

int session_run(const std::vector<std::string>& argv) {
  const Arguments args(session_run_options(), argv);
  if (args.help_requested()) return print_help(session_run_help(), args);
  args.require({"db", "participant"});
  // The options checked before the study is opened; the protocol's defaults after.
  const std::string world = args.choice("world", {"proxy", "soft"});
  if (args.has("tracker")) check_tracker(args.text("tracker"));
  const std::string display = args.choice("display", {"none", "headset"});
  store::StudyStore store(args.text("db"));
  const studies::Protocol protocol = studies::stored_protocol(store);
  const std::string tracker =
      args.has("tracker") ? args.text("tracker") : protocol_tracker(protocol);
  const bool in_headset = args.has("display")
                              ? display == "headset"
                              : protocol.default_display == studies::SessionDisplay::kHeadset;
  const std::uint64_t seed = args.seed("seed");
  const bool quiet = args.flag("quiet") || args.text("json") == "-";
  std::mutex out;  // the session's lines and the headset's, from two threads
  const auto say = [quiet, &out](const std::string& line) {
    std::lock_guard lock(out);
    if (!quiet) std::cout << line << std::endl;
  };
  studies::SessionControl control;
  // In the headset, OpenXR's hands come from the headset's own session.
  std::unique_ptr<studies::SessionHeadset> headset;
  if (in_headset) headset = open_headset(control, protocol, say, tracker == "openxr");
  const studies::TrackerPtr kind = tracker == "scripted"    ? studies::scripted_tracker()
                                   : tracker == "simulated" ? studies::simulated_tracker(seed)
                                   : tracker == "openxr"    ? studies::openxr_tracker(headset.get())
                                                            : studies::recording_tracker(tracker);
  studies::PipelineTrialDriver driver(kind, 120.0, world_kind(args));
  studies::SessionRunner runner(store, driver,
                                kind->own_answers().value_or(studies::fixed_responder()));
  if (headset) {
    runner.attach(&control);
    driver.attach(&control);
    driver.set_real_time(true);  // the participant sees the trial as it happens
  }
  const auto start = std::chrono::steady_clock::now();
  const studies::SessionReport report = runner.run(
      args.text("participant"), world == "soft" ? kind->name() + " (soft hand)" : kind->name(),
      args.flag("resume"), say);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::optional<xr::HeadsetCounts> shown;
  if (headset) {
    headset->close();
    shown = headset->counts();
    if (!headset->error().empty())
      std::cerr << "handlab-cli session: the headset: " << headset->error() << "\n";
  }
  if (args.text("json") != "-")
    print_session_report(args.text("participant"), report, seconds, shown);
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_session_json(out, args.text("participant"), report, seconds, shown);
    });
  return 0;
}

std::vector<OptionSpec> session_decision_options() {
  return {
      {"db", "DB", "the study database"},
      {"participant", "ID", "an enrolled participant"},
      {"trial", "N", "the trial's number in the schedule (1-based, as status shows it)"},
      {"reason", "TEXT", "why: kept in the record"},
  };
}

CommandHelp session_decision_help(bool redo) {
  return redo ? CommandHelp{"session redo",
                            {"db participant trial reason"},
                            "Marks a trial's result as redone (kept) so the next session run "
                            "runs it again."}
              : CommandHelp{"session skip",
                            {"db participant trial reason"},
                            "Records a planned trial as skipped; runs go on past it."};
}

int session_decision(const std::vector<std::string>& argv, bool redo) {
  const Arguments args(session_decision_options(), argv);
  if (args.help_requested()) return print_help(session_decision_help(redo), args);
  args.require({"db", "participant", "trial", "reason"});
  store::StudyStore store(args.text("db"));
  const std::string id = args.text("participant");
  if (!store.participant(id)) throw std::runtime_error("no participant " + id);
  const int position = int(args.integer("trial")) - 1;
  if (redo) {
    store.redo_trial(id, position, args.text("reason"));
    std::cout << id << " trial " << position + 1 << " will run again\n";
  } else {
    studies::skip_trial_between_sessions(store, id, position, args.text("reason"));
    std::cout << id << " trial " << position + 1 << " skipped\n";
  }
  return 0;
}

}  // namespace

int run_session(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::cout << family_usage({{session_run_help(), session_run_options()},
                               {session_decision_help(true), session_decision_options()},
                               {session_decision_help(false), session_decision_options()}});
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "run") return session_run(rest);
  if (argv[0] == "redo") return session_decision(rest, true);
  if (argv[0] == "skip") return session_decision(rest, false);
  throw UsageError("unknown session command '" + argv[0] + "' (run, redo, skip)");
}

}  // namespace handlab::cli
