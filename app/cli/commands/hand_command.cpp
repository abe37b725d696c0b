// handlab-cli hand: the simulated hand's skin and flesh, or the tracked (Leap) skeleton,
// for a given size; files to look at and a picture.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/commands/commands.h"
#include "app/cli/output_file.h"
#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/mesh/mesh_io.h"
#include "core/render/hand_drawing.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"
#include "core/util/json_writer.h"

namespace handlab::cli {

int run_hand(const std::vector<std::string>& argv) {
  const std::vector<OptionSpec> specs = {
      {"length", "METRES", "hand length, wrist crease to middle fingertip", "0.214"},
      {"breadth", "METRES", "hand breadth across the MCPs (default 0.45 x length)"},
      {"left", "", "a left hand (default right)"},
      {"subdivisions", "N", "Catmull-Clark levels of the skin (1 = study resolution)", "1"},
      {"out", "FILE", "write the skin as Wavefront OBJ"},
      {"png", "FILE", "draw the hand offscreen into a PNG"},
      {"json", "OUT", "write sizes and mesh figures as JSON (- for standard output)"},
  };
  const Arguments args(specs, argv);
  if (args.help_requested()) {
    std::cout << "Usage: handlab-cli hand [--length 0.214] [--out hand.obj] [--png hand.png]\n\n"
                 "Builds the simulated hand (16 bones, skin) of the given size.\n\nOptions:\n"
              << format_options_help(specs);
    return 0;
  }
  hand::HandShape shape = hand::HandShape::with_length(args.number("length"));
  if (shape.length < 0.10 || shape.length > 0.30)
    throw UsageError("--length must be between 0.10 and 0.30 m");
  if (args.has("breadth")) shape.breadth = args.number("breadth");
  shape.left = args.flag("left");
  const long subdivisions = args.integer("subdivisions");
  if (subdivisions < 0 || subdivisions > 3) throw UsageError("--subdivisions must be 0 to 3");

  const hand::Skeleton skeleton = hand::build_simulated_hand(shape);
  const hand::HandSkin skin = hand::build_skin(skeleton, shape, int(subdivisions));
  std::cout << "simulated hand: length " << shape.length * 100 << " cm (skin measures "
            << skin.measured_length * 100 << " cm), " << skeleton.bones.size() << " bones, "
            << skeleton.dofs.size() << " joint DOFs, skin " << skin.surface.vertices.size()
            << " vertices, " << skin.surface.triangles.size() << " triangles\n";
  if (args.has("out")) mesh::write_obj(skin.surface, args.text("out"));
  if (args.has("png")) {
    render::DrawList list;
    Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
    // Palm down over the floor, fingers pointing away from the viewer.
    placement.linear() << -1, 0, 0, 0, 0, -1, 0, -1, 0;
    placement.translation() = Eigen::Vector3d(0, 0.08, 0.05);
    list.items.push_back(render::draw_task_scene({}, Eigen::Isometry3d::Identity()).items.front());
    render::draw_skin(list, skin.surface.vertices, skin.surface.triangles, placement,
                      {0.86f, 0.67f, 0.56f, 1.0f});
    render::OrbitCamera camera;
    camera.target = Eigen::Vector3f(0, 0.08f, -0.05f);
    camera.distance = 0.42f;
    camera.pitch = 0.9f;
    camera.yaw = 0.35f;
    render::OffscreenRenderer renderer(900, 700);
    render::write_png(renderer.render(list, camera), args.text("png"));
  }
  if (args.has("json")) {
    write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter json(out);
      json.begin_object()
          .field("length_m", shape.length)
          .field("measured_length_m", skin.measured_length);
      json.field("bones", skeleton.bones.size()).field("dofs", skeleton.dofs.size());
      json.field("skin_vertices", skin.surface.vertices.size())
          .field("skin_triangles", skin.surface.triangles.size());
      json.end_object();
    });
  }
  return 0;
}

}  // namespace handlab::cli
