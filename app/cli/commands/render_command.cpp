// handlab-cli render: draws the task scene offscreen (OSMesa) into a PNG, no display needed;
// with --db, a moment of a stored trial from its frame log.
#include <cstdio>
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/hand/simulated_hand.h"
#include "core/render/frame_drawing.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"
#include "studies/session/trial_replay.h"

namespace handlab::cli {

namespace {

std::vector<OptionSpec> render_options() {
  return {
      {"out", "FILE", "PNG file to write", "scene.png"},
      {"width", "PIXELS", "image width", "800"},
      {"height", "PIXELS", "image height", "600"},
      {"cube", "METRES", "cube edge length (0.06 gross, 0.01 fine)", "0.06"},
      {"yaw", "RAD", "camera yaw about the vertical", "0.6"},
      {"pitch", "RAD", "camera pitch above the horizon", "0.55"},
      {"distance", "METRES", "camera distance from the target", "0.75"},
      {"samples", "N", "multisample anti-aliasing samples (1 = off)", "4"},
      {"db", "DB",
       "a study database: draw a moment of one of its trials (needs --participant, --trial)"},
      {"participant", "ID", "with --db: the participant"},
      {"trial", "N", "with --db: the trial's number in the schedule (1-based, as status shows it)"},
      {"attempt", "K", "with --db: the attempt (default: the latest with logged frames)"},
      {"time", "SECONDS", "with --db: the moment, in s from the trial's start (default: its end)"},
  };
}

CommandHelp render_help() {
  return {"render",
          {},
          "Draws the task scene (floor, zones A and B, the cube at A) offscreen with\n"
          "OSMesa and writes it as a PNG. Needs no display. With --db, --participant\n"
          "and --trial: the trial as its frame log stored it at --time (the simulated\n"
          "hand's bones, the cube, the zones), the condition's cube."};
}

}  // namespace

int run_render(const std::vector<std::string>& argv) {
  const Arguments args(render_options(), argv);
  if (args.help_requested()) return print_help(render_help(), args);
  const long width = args.integer("width"), height = args.integer("height");
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw UsageError("--width and --height must be between 16 and 8192 pixels");
  const double cube = args.number("cube");
  if (cube <= 0.0 || cube > 0.5) throw UsageError("--cube must be in (0, 0.5] metres");

  render::OrbitCamera camera;
  camera.yaw = float(args.number("yaw"));
  camera.pitch = float(args.number("pitch"));
  camera.distance = float(args.number("distance"));
  render::DrawList list;
  std::string what;
  if (args.has("db")) {
    if (!args.has("participant") || !args.has("trial"))
      throw UsageError("--db needs --participant and --trial");
    const long trial = args.integer("trial");
    const long attempt = args.has("attempt") ? args.integer("attempt") : 0;
    if (trial < 1) throw UsageError("--trial counts from 1");
    if (args.has("attempt") && attempt < 1) throw UsageError("--attempt counts from 1");
    store::StudyStore store(args.text("db"), store::StudyStore::Access::kReadOnly);
    const studies::TrialReplay replay =
        studies::load_trial_replay(store, args.text("participant"), int(trial - 1), int(attempt));
    const double time = args.has("time") ? args.number("time") : replay.duration();
    if (time < 0.0) throw UsageError("--time must be 0 or more seconds");
    const store::FrameRecord& frame = replay.frame_at(time);
    list = render::draw_stored_frame(
        replay.layout, render::make_bone_meshes(hand::build_simulated_hand(replay.simulated_hand)),
        frame);
    char at[64];
    std::snprintf(at, sizeof at, "%.2f s of %.2f s", frame.time, replay.duration());
    what = ": " + replay.participant + " trial " + std::to_string(trial) + " (attempt " +
           std::to_string(replay.attempt) + ", " + replay.condition + ") at " + at;
  } else {
    task::SceneLayout layout;
    layout.cube_size = cube;
    list = render::draw_task_scene(layout, task::cube_start_pose(layout));
  }
  render::OffscreenRenderer renderer(int(width), int(height), int(args.integer("samples")));
  const render::Image image = renderer.render(list, camera);
  const std::string out = args.text("out");
  render::write_png(image, out);
  std::cout << "wrote " << out << " (" << width << "x" << height << ")" << what << "\n";
  return 0;
}

}  // namespace handlab::cli
