// handlab-cli tracking: what a recording holds, and its frames as CSV.
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/tracking/hand_fitting.h"
#include "core/tracking/openxr_hand.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

std::vector<OptionSpec> tracking_info_options() {
  return {
      {"json", "OUT", "write the figures as JSON (- for standard output)"},
      {"fit", "", "also fit every hand with the tracked skeleton measured from the recording"},
      {"via-openxr", "",
       "read every hand as OpenXR's hand tracking gives it: its 26 joints (XR_EXT_hand_tracking), "
       "then the tracked hand made from them"}};
}

CommandHelp tracking_info_help() {
  return {"tracking info",
          {"FILE [json] [fit] [via-openxr]"},
          "Format, frames, hands, duration, frame rate, rejected frames and the thumb-index tip "
          "distance range of a recording (.json, .json.lz, .hlrec)."};
}

// A recording's figures: its frames, hands, length in time and thumb-index range.
struct RecordingFigures {
  std::size_t with_hands = 0, left = 0, right = 0;
  double lo = INFINITY, hi = -INFINITY;  // m: the thumb-index tip distance's range
  double duration = 0.0, fps = 0.0;
  std::map<std::string, int> reasons;  // rejected frames, by reason
};

RecordingFigures figures_of(const tracking::Recording& r) {
  RecordingFigures g;
  for (const auto& f : r.frames) {
    g.with_hands += !f.hands.empty();
    for (const auto& h : f.hands) {
      (h.side == tracking::Side::kLeft ? g.left : g.right) += 1;
      g.lo = std::min(g.lo, tracking::thumb_index_distance(h));
      g.hi = std::max(g.hi, tracking::thumb_index_distance(h));
    }
  }
  g.duration = r.frames.size() > 1 ? r.frames.back().timestamp - r.frames.front().timestamp : 0.0;
  g.fps = g.duration > 0 ? double(r.frames.size() - 1) / g.duration : 0.0;
  for (const auto& rej : r.rejected) ++g.reasons[rej.reason];
  return g;
}

// --via-openxr: each hand as an OpenXR runtime would give it, then read back as a tracked hand.
void pass_through_openxr(tracking::Recording& r) {
  for (auto& f : r.frames)
    for (auto& h : f.hands)
      h = *tracking::tracked_hand_from_openxr(tracking::openxr_hand_from_tracked(h), h.id);
}

// --fit: each hand fitted with the skeleton measured from the recording.
struct FitFigures {
  std::string side;
  double hand_length, mean_rms, max;
  int frames;
};

std::vector<FitFigures> fits_of(const tracking::Recording& r) {
  std::vector<FitFigures> fits;
  for (tracking::Side side : {tracking::Side::kLeft, tracking::Side::kRight}) {
    auto fitter = tracking::TrackedHandFitter::for_recording(r.frames, side);
    if (!fitter) continue;
    FitFigures figures{side == tracking::Side::kLeft ? "left" : "right",
                       *tracking::estimate_hand_length(r.frames, side), 0, 0, 0};
    for (const auto& f : r.frames)
      if (const auto* h = f.hand(side)) {
        const auto fit = fitter->fit(*h);
        figures.mean_rms += fit.rms_residual;
        figures.max = std::max(figures.max, fit.max_residual);
        ++figures.frames;
      }
    figures.mean_rms /= std::max(figures.frames, 1);
    fits.push_back(figures);
  }
  return fits;
}

void print_info(const tracking::Recording& r, const RecordingFigures& g,
                const std::vector<FitFigures>& fits, bool via_openxr) {
  std::cout << r.source << (via_openxr ? " (read through OpenXR's 26 joints)" : "")
            << "\n  format version   " << r.format_version << "\n  frames           "
            << r.frames_in_file << " (" << r.frames.size() << " read, " << g.with_hands
            << " with hands)\n  hands            " << g.left << " left, " << g.right
            << " right\n  duration         " << std::fixed << std::setprecision(3) << g.duration
            << " s\n  mean frame rate  " << std::setprecision(1) << g.fps
            << " Hz\n  rejected         " << r.rejected.size() << "\n";
  for (const auto& [reason, count] : g.reasons)
    std::cout << "    " << count << " x " << reason << "\n";
  if (std::isfinite(g.lo))
    std::cout << "  thumb-index tip  " << g.lo * 1000 << " to " << g.hi * 1000 << " mm\n";
  for (const auto& f : fits)
    std::cout << "  fit, " << std::left << std::setw(11) << (f.side + " hand") << "hand length "
              << f.hand_length * 100 << " cm, residual mean " << f.mean_rms * 1000 << " mm, max "
              << f.max * 1000 << " mm over " << f.frames << " frames\n";
}

void write_info_json(std::ostream& out, const tracking::Recording& r, const RecordingFigures& g,
                     const std::vector<FitFigures>& fits, bool via_openxr) {
  util::JsonWriter json(out);
  json.begin_object().field("source", r.source).field("format_version", r.format_version);
  json.field("via_openxr", via_openxr);
  json.field("frames", r.frames_in_file)
      .field("frames_read", r.frames.size())
      .field("frames_with_hands", g.with_hands);
  json.key("hands").begin_object().field("left", g.left).field("right", g.right).end_object();
  json.field("duration_s", g.duration).field("fps_mean", g.fps);
  json.key("rejected").begin_array();
  for (const auto& rej : r.rejected)
    json.begin_object().field("frame", rej.index).field("reason", rej.reason).end_object();
  json.end_array();
  json.key("thumb_index_mm").begin_object();
  if (std::isfinite(g.lo))
    json.field("min", g.lo * 1000).field("max", g.hi * 1000);
  else
    json.key("min").null().key("max").null();
  json.end_object();
  if (!fits.empty()) {
    json.key("fit").begin_array();
    for (const auto& f : fits)
      json.begin_object()
          .field("side", f.side)
          .field("hand_length_m", f.hand_length)
          .field("frames", f.frames)
          .field("residual_mean_mm", f.mean_rms * 1000)
          .field("residual_max_mm", f.max * 1000)
          .end_object();
    json.end_array();
  }
  json.end_object();
}

int tracking_info(const std::vector<std::string>& argv) {
  const Arguments args(tracking_info_options(), argv, 1);
  if (args.help_requested()) return print_help(tracking_info_help(), args);
  if (args.positional().empty()) throw UsageError("name a recording");
  tracking::Recording r = tracking::read_recording(args.positional()[0]);
  if (args.flag("via-openxr")) pass_through_openxr(r);
  const RecordingFigures figures = figures_of(r);
  const std::vector<FitFigures> fits = args.flag("fit") ? fits_of(r) : std::vector<FitFigures>{};
  const bool via_openxr = args.flag("via-openxr");
  if (args.text("json") != "-") print_info(r, figures, fits, via_openxr);
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_info_json(out, r, figures, fits, via_openxr);
    });
  return 0;
}

std::vector<OptionSpec> tracking_convert_options() {
  return {{"out", "FILE", "CSV (one row per hand per frame) or .hlrec"}};
}

CommandHelp tracking_convert_help() {
  return {"tracking convert",
          {"FILE out"},
          "Writes every hand of every frame with all its joints (metres, seconds), or handlab's "
          "own recording."};
}

int tracking_convert(const std::vector<std::string>& argv) {
  const Arguments args(tracking_convert_options(), argv, 1);
  if (args.help_requested()) return print_help(tracking_convert_help(), args);
  if (args.positional().empty() || !args.has("out"))
    throw UsageError("name a recording and --out FILE");
  const tracking::Recording r = tracking::read_recording(args.positional()[0]);
  const std::string out_path = args.text("out");
  if (out_path.size() > 6 && out_path.compare(out_path.size() - 6, 6, ".hlrec") == 0) {
    tracking::write_hlrec(r.frames, out_path);
  } else {
    util::write_output(out_path, [&](std::ostream& out) {
      out << std::setprecision(17);
      static const char* digits[5] = {"thumb", "index", "middle", "ring", "pinky"};
      static const char* joints[5] = {"carp", "mcp", "pip", "dip", "tip"};
      out << "frame_id,timestamp_s,hand_id,side,confidence,pinch_strength,grab_strength,derived";
      for (const char* v : {"palm", "palm_normal", "direction", "wrist"})
        for (const char* c : {"x", "y", "z"}) out << ',' << v << '_' << c;
      for (const char* d : digits)
        for (const char* j : joints)
          for (const char* c : {"x", "y", "z"}) out << ',' << d << '_' << j << '_' << c;
      out << '\n';
      for (const auto& f : r.frames)
        for (const auto& h : f.hands) {
          out << f.id << ',' << f.timestamp << ',' << h.id << ','
              << (h.side == tracking::Side::kLeft ? "left" : "right") << ',' << h.confidence << ','
              << h.pinch_strength << ',' << h.grab_strength << ',' << int(h.derived);
          for (const auto* v : {&h.palm_position, &h.palm_normal, &h.direction, &h.wrist})
            for (int c = 0; c < 3; ++c) out << ',' << (*v)[c];
          for (const auto& digit : h.joints)
            for (const auto& p : digit)
              for (int c = 0; c < 3; ++c) out << ',' << p[c];
          out << '\n';
        }
    });
  }
  std::cout << "wrote " << out_path << " (" << r.frames.size() << " frames)\n";
  return 0;
}

}  // namespace

int run_tracking(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::cout << family_usage({{tracking_info_help(), tracking_info_options()},
                               {tracking_convert_help(), tracking_convert_options()}})
              << "\nReads Leap Motion recordings (LeapJS Playback .json/.json.lz, formatVersion "
                 "0.1, 1, 2) and handlab's .hlrec.\n";
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "info") return tracking_info(rest);
  if (argv[0] == "convert") return tracking_convert(rest);
  throw UsageError("unknown tracking command '" + argv[0] + "' (info, convert)");
}

}  // namespace handlab::cli
