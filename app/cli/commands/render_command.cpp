// handlab-cli render: draws the task scene offscreen (OSMesa) into a PNG, no display needed.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/commands/commands.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"

namespace handlab::cli {

int run_render(const std::vector<std::string>& argv) {
  const std::vector<OptionSpec> specs = {
      {"out", "FILE", "PNG file to write", "scene.png"},
      {"width", "PIXELS", "image width", "800"},
      {"height", "PIXELS", "image height", "600"},
      {"cube", "METRES", "cube edge length (0.06 gross, 0.01 fine)", "0.06"},
      {"yaw", "RAD", "camera yaw about the vertical", "0.6"},
      {"pitch", "RAD", "camera pitch above the horizon", "0.55"},
      {"distance", "METRES", "camera distance from the target", "0.75"},
      {"samples", "N", "multisample anti-aliasing samples (1 = off)", "4"},
  };
  const Arguments args(specs, argv);
  if (args.help_requested()) {
    std::cout << "Usage: handlab-cli render [options]\n\n"
                 "Draws the task scene (floor, zones A and B, the cube at A) offscreen with\n"
                 "OSMesa and writes it as a PNG. Needs no display.\n\nOptions:\n"
              << format_options_help(specs);
    return 0;
  }
  const long width = args.integer("width"), height = args.integer("height");
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw UsageError("--width and --height must be between 16 and 8192 pixels");
  const double cube = args.number("cube");
  if (cube <= 0.0 || cube > 0.5) throw UsageError("--cube must be in (0, 0.5] metres");

  task::SceneLayout layout;
  layout.cube_size = cube;
  render::OrbitCamera camera;
  camera.yaw = float(args.number("yaw"));
  camera.pitch = float(args.number("pitch"));
  camera.distance = float(args.number("distance"));
  render::OffscreenRenderer renderer(int(width), int(height), int(args.integer("samples")));
  const render::Image image =
      renderer.render(render::draw_task_scene(layout, task::cube_start_pose(layout)), camera);
  const std::string out = args.text("out");
  render::write_png(image, out);
  std::cout << "wrote " << out << " (" << width << "x" << height << ")\n";
  return 0;
}

}  // namespace handlab::cli
