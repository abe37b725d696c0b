// handlab-cli sim pinches: every closing of thumb and index in real recordings, retargeted by
// Naive and by Ours onto the study hand, with a cube of each size placed where the pads reach
// its faces, then the scripted lift and hold (core/task/recorded_pinches.h): held or lost, and
// why. The grasp map's question asked of real hands.
#include "app/cli/commands/sim_pinches.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "analysis/stats/wilson_interval.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/sim_grasp.h"
#include "app/cli/progress_line.h"
#include "core/hand/flesh.h"
#include "core/hand/hand_shape.h"
#include "core/retarget/recording_poses.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/recorded_pinches.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "core/util/parallel_runs.h"

namespace handlab::cli {
namespace {

// The simulated hand a recording's poses drive (its side's) with one cube.
struct PinchHand {
  hand::Skeleton skeleton;
  sim::HandSimModel model;
};

// One closing's run: its recording, strategy and cube, the closing and what became of it.
struct PinchRow {
  std::string recording, strategy;
  double cube_size = 0.0;
  double start = 0.0;  // s: the recording's first frame
  sim::RecordedClosing closing;
  sim::RecordedPinchRun run;  // when the closing takes the cube
  std::shared_ptr<const PinchHand> hand;
  sim::PinchScript script;
};

// Why a closing was not run, or what became of its cube.
std::string outcome(const PinchRow& r) {
  if (!r.closing.takes_cube)
    return r.closing.widest < r.cube_size ? "not run: opened short of the side"
                                          : "not run: closed short of the side";
  return sim::pinch_loss_name(r.run.loss);
}

// Every closing of each recording, strategy and cube, with its hand and script.
std::vector<PinchRow> prepare(const std::vector<std::string>& recordings,
                              const std::vector<std::string>& strategies,
                              const std::vector<double>& cubes,
                              const sim::SimParameters& parameters) {
  std::vector<PinchRow> rows;
  for (const std::string& path : recordings) {
    const tracking::Recording recording = tracking::read_recording(path);
    std::vector<std::shared_ptr<const PinchHand>> hands;  // a cube each, of the recording's side
    for (const std::string& strategy : strategies) {
      const retarget::RecordingPoses poses = retarget::retarget_recording(
          recording, strategy == "naive" ? retarget::Strategy::kNaive : retarget::Strategy::kOurs);
      for (std::size_t c = 0; c < cubes.size(); ++c) {
        if (hands.size() <= c) {
          sim::SimParameters p = parameters;
          p.cube_size = cubes[c];
          hands.push_back(std::make_shared<const PinchHand>(
              PinchHand{poses.skeleton,
                        sim::make_hand_sim_model(
                            poses.skeleton, hand::build_flesh(poses.skeleton, poses.shape), p)}));
        }
        const PinchHand& h = *hands[c];
        for (const sim::RecordedClosing& closing :
             sim::find_recorded_closings(h.skeleton, h.model, poses.times, poses.poses))
          rows.push_back({path,
                          strategy,
                          cubes[c],
                          poses.times.front(),
                          closing,
                          {},
                          hands[c],
                          closing.takes_cube
                              ? sim::make_recorded_pinch_script(h.skeleton, h.model, poses.times,
                                                                poses.poses, closing)
                              : sim::PinchScript{}});
      }
    }
  }
  return rows;
}

void print_rows(const std::vector<PinchRow>& rows) {
  std::printf("%-22s %-6s %5s %7s %7s %7s %6s %6s  %-15s %6s %6s %6s %6s\n", "recording", "strat",
              "cube", "moment", "widest", "least", "speed", "tilt", "outcome", "pushed", "grip",
              "slip", "other");
  std::printf("%-22s %-6s %5s %7s %7s %7s %6s %6s  %-15s %6s %6s %6s %6s\n", "", "", "mm", "s",
              "mm", "mm", "cm/s", "deg", "", "mm", "N", "mm", "mm");
  for (const PinchRow& r : rows) {
    const std::string name = std::filesystem::path(r.recording).filename().string();
    std::printf("%-22s %-6s %5.0f %7.2f %7.1f %7.1f %6.1f %6.1f  %-15s", name.c_str(),
                r.strategy.c_str(), 1000 * r.cube_size, r.closing.moment - r.start,
                1000 * r.closing.widest, 1000 * r.closing.narrowest, 100 * r.closing.closing_speed,
                r.closing.tilt * 180 / M_PI, outcome(r).c_str());
    if (r.closing.takes_cube)
      std::printf(" %6.1f %6.2f %6.2f %6.1f", r.run.pushed_mm, r.run.grip_at_lift_n,
                  r.run.report.slip_mm, -1000 * r.script.pinch_clearance);
    std::printf("\n");
  }
  // Per strategy and cube, over the recordings.
  std::vector<double> cubes;
  for (const PinchRow& r : rows)
    if (std::find(cubes.begin(), cubes.end(), r.cube_size) == cubes.end())
      cubes.push_back(r.cube_size);
  for (const char* strategy : {"naive", "ours"})
    for (double cube : cubes) {
      int run = 0, held = 0;
      for (const PinchRow& r : rows)
        if (r.strategy == strategy && r.cube_size == cube && r.closing.takes_cube)
          ++run, held += r.run.report.held;
      if (run == 0) continue;
      const stats::ProportionInterval ci = stats::wilson_interval(held, run);
      std::printf("%s, %.0f mm cube: held %d of %d (%.0f %%, 95 %% CI %.0f-%.0f %%)\n", strategy,
                  1000 * cube, held, run, 100.0 * held / run, 100 * ci.low, 100 * ci.high);
    }
}

void write_rows_json(const std::vector<PinchRow>& rows, const std::vector<std::string>& physics,
                     std::ostream& out) {
  util::JsonWriter json(out);
  json.begin_object();
  write_physics(json, physics);
  json.key("pinches").begin_array();
  for (const PinchRow& r : rows) {
    json.begin_object()
        .field("recording", r.recording)
        .field("strategy", r.strategy)
        .field("cube_size_m", r.cube_size)
        .field("moment_s", r.closing.moment - r.start)
        .field("closed_s", r.closing.closed - r.start)
        .field("widest_m", r.closing.widest)
        .field("narrowest_m", r.closing.narrowest)
        .field("closing_speed_m_s", r.closing.closing_speed)
        .field("tilt_deg", r.closing.tilt * 180 / M_PI)
        .field("takes_cube", r.closing.takes_cube)
        .field("outcome", outcome(r));
    if (r.closing.takes_cube) {
      json.field("pushed_mm", r.run.pushed_mm)
          .field("grip_at_lift_n", r.run.grip_at_lift_n)
          // null where a pad never touched the cube (NaN is written as null)
          .field("touch_lead_ms", r.run.touch_lead_ms.value_or(std::nan("")))
          .field("turn_at_touch_deg", r.run.turn_at_touch_deg.value_or(std::nan("")))
          .field("other_skin_depth_mm", -1000 * r.script.pinch_clearance);
      write_pinch_measures(json, r.run.report);
    }
    json.end_object();
  }
  json.end_array().end_object();
}

}  // namespace

std::vector<OptionSpec> sim_pinches_options() {
  std::vector<OptionSpec> specs = {
      {"recording", "FILE", "a recording (.json.lz) whose closings to run; repeatable", "", true},
      {"strategy", "naive|ours", "a retargeting to run them by; repeatable (default: both)", "",
       true},
      {"cube", "SIDE", "a cube's side in metres; repeatable (default: 0.01 and 0.06)", "", true},
      {"jobs", "J", "pinches run side by side (default: the machine's cores)", "0"},
      {"json", "OUT", "write every pinch's closing and outcome as JSON (- for standard output)"},
  };
  specs.push_back(physics_option());
  return specs;
}

CommandHelp sim_pinches_help() {
  return {"sim pinches",
          {"recording [strategy] [cube] [physics] [jobs] [json]"},
          "Every closing of thumb and index in the recordings (the pads' aperture falling by 1 "
          "cm or more), retargeted onto the 21.4 cm study hand, runs on the soft hand with a "
          "cube placed where the pads reach its faces (the hand turned and moved so that the "
          "cube rests on the floor between them), the fingers kept where the closing ends, then "
          "lifted 10 cm and held 2 s. Reports per closing its moment, widest and least aperture, "
          "the pads' speed and tilt, whether the cube was held and, if not, why: pushed away (a "
          "quarter of its side along the floor by the closing's end, no grip as the lift "
          "starts), squeezed out (no grip otherwise) or slipped at the lift (docs/simulator.md), "
          "and how deep the skin but the pads' lies in the cube at the least aperture (other, "
          "mm; below 0: clear of it)."};
}

int sim_pinches(const std::vector<std::string>& argv) {
  const Arguments args(sim_pinches_options(), argv);
  if (args.help_requested()) return print_help(sim_pinches_help(), args);
  const std::vector<std::string> recordings = args.all("recording");
  if (recordings.empty()) throw UsageError("name recordings with --recording FILE");
  std::vector<std::string> strategies;
  for (const std::string& s : args.all("strategy")) {
    if (s != "naive" && s != "ours") throw UsageError("--strategy must be naive or ours");
    strategies.push_back(s);
  }
  if (strategies.empty()) strategies = {"naive", "ours"};
  const std::vector<double> cubes = cube_sides(args);
  const int jobs = job_count(args);

  sim::SimParameters parameters;
  apply_physics_option(args, parameters);
  std::vector<PinchRow> rows = prepare(recordings, strategies, cubes, parameters);
  sim::SimOptions options;
  if (jobs > 1) options.threads = 1;
  const bool to_stdout = args.text("json") == "-";
  ProgressLine progress(to_stdout);
  const auto start = std::chrono::steady_clock::now();
  util::run_in_parallel(
      rows.size(), jobs,
      [&](std::size_t i) {
        PinchRow& row = rows[i];
        if (row.closing.takes_cube)
          row.run =
              sim::run_recorded_pinch(row.hand->model, row.hand->skeleton, row.script, options);
      },
      [&](int done) {
        char text[100];
        std::snprintf(
            text, sizeof text, "pinches %d/%zu  %.0f s", done, rows.size(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        progress.show(done, text);
      });
  progress.finish();
  if (!to_stdout) print_rows(rows);
  if (args.has("json"))
    util::write_output(args.text("json"),
                       [&](std::ostream& out) { write_rows_json(rows, args.all("physics"), out); });
  return 0;
}

}  // namespace handlab::cli
