// handlab-cli hand: the simulated hand's skin and flesh, or the tracked (Leap) skeleton,
// for a given size; files to look at and a picture.
#include <iostream>

#include <optional>
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/util/output_file.h"

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/hand/tracked_hand.h"
#include "core/mesh/mesh_io.h"
#include "core/render/hand_drawing.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"
#include "core/util/json_writer.h"

namespace handlab::cli {
namespace {

// Palm down over the floor, fingers pointing away from the viewer, shifted along x.
Eigen::Isometry3d hand_placement(double x) {
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  placement.linear() << -1, 0, 0, 0, 0, -1, 0, -1, 0;
  placement.translation() = Eigen::Vector3d(x, 0.06, 0.08);
  return placement;
}

render::Image render_hands(const render::DrawList& list, bool wide = false) {
  render::OrbitCamera camera;
  camera.target = Eigen::Vector3f(0, 0.04f, -0.03f);
  camera.distance = wide ? 0.55f : 0.42f;
  camera.pitch = 0.95f;
  camera.yaw = 0.0f;
  render::OffscreenRenderer renderer(wide ? 1200 : 900, 700);
  return renderer.render(list, camera);
}

}  // namespace

namespace {

std::vector<OptionSpec> hand_options() {
  return {
      {"length", "METRES", "hand length, wrist crease to middle fingertip", "0.214"},
      {"breadth", "METRES", "hand breadth across the MCPs (default 0.45 x length)"},
      {"left", "", "a left hand (default right)"},
      {"subdivisions", "N", "Catmull-Clark levels of the skin (1 = study resolution)", "1"},
      {"out", "FILE", "write the skin as Wavefront OBJ"},
      {"tets", "FILE", "tetrahedralise the flesh (TetGen) and write it as legacy ASCII VTK"},
      {"resolution", "N", "flesh resolution: 1 (study), 4 or 16 times more tets", "1"},
      {"tracked", "", "the tracked (Leap) skeleton instead of the simulated hand"},
      {"pair", "", "with --png: the simulated hand and a tracked skeleton side by side"},
      {"tracked-length", "METRES", "with --pair: the tracked hand's length", "0.18"},
      {"png", "FILE", "draw the hand offscreen into a PNG"},
      {"json", "OUT", "write sizes and mesh figures as JSON (- for standard output)"},
  };
}

CommandHelp hand_help() {
  return {"hand",
          {"[length] [out] [png] [options]"},
          "Builds the simulated hand (16 bones, skin) of the given size."};
}

}  // namespace

namespace {

// --tracked: the Leap skeleton of the shape, its bones' lengths, and its picture and JSON.
void show_tracked(const Arguments& args, const hand::HandShape& shape) {
  const hand::Skeleton tracked = hand::build_tracked_hand(shape);
  const hand::LeapJoints joints = hand::to_leap_joints(tracked, hand::HandPose::rest(tracked));
  std::cout << "tracked (Leap) skeleton: length " << shape.length * 100 << " cm, "
            << tracked.bones.size() << " bones, " << tracked.dofs.size() << " joint DOFs\n";
  for (int f = 0; f < hand::kFingerCount; ++f) {
    std::cout << "  " << hand::finger_name(f) << ":";
    for (int k = 0; k + 1 < 5; ++k)
      std::cout << " "
                << (joints.joints[std::size_t(f)][std::size_t(k + 1)] -
                    joints.joints[std::size_t(f)][std::size_t(k)])
                           .norm() *
                       1000;
    std::cout << " mm\n";
  }
  if (args.has("png")) {
    render::DrawList list;
    list.items.push_back(render::draw_task_scene({}, Eigen::Isometry3d::Identity()).items.front());
    render::draw_skeleton(list, tracked, hand::HandPose::rest(tracked), hand_placement(0.0),
                          {0.35f, 0.6f, 0.85f, 1.0f}, {0.95f, 0.95f, 0.95f, 1.0f});
    render::write_png(render_hands(list), args.text("png"));
  }
  if (args.has("json")) {
    util::write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter json(out);
      json.begin_object().field("length_m", shape.length).field("bones", tracked.bones.size());
      json.field("dofs", tracked.dofs.size()).key("joints_m").begin_object();
      for (int f = 0; f < hand::kFingerCount; ++f) {
        json.key(hand::finger_name(f)).begin_array();
        for (const auto& p : joints.joints[std::size_t(f)])
          json.begin_array().value(p.x()).value(p.y()).value(p.z()).end_array();
        json.end_array();
      }
      json.end_object().end_object();
    });
  }
}

// --tets: the flesh tetrahedralised, written and measured.
hand::HandFlesh write_flesh(const Arguments& args, const hand::Skeleton& skeleton,
                            const hand::HandShape& shape) {
  hand::FleshOptions options;
  options.resolution = int(args.integer("resolution"));
  if (options.resolution != 1 && options.resolution != 4 && options.resolution != 16)
    throw UsageError("--resolution must be 1, 4 or 16");
  hand::HandFlesh flesh = hand::build_flesh(skeleton, shape, options);
  mesh::write_vtk(flesh.tets, args.text("tets"));
  const auto& q = flesh.quality;
  std::cout << "flesh: " << q.tets << " tets, " << flesh.tets.nodes.size()
            << " nodes, radius-edge ratio <= " << q.max_radius_edge_ratio << ", minimum dihedral "
            << q.min_dihedral_deg << " deg, " << flesh.coupling.size() << " coupling points\n";
  return flesh;
}

// --png: the skin, beside a tracked skeleton with --pair.
void draw_simulated(const Arguments& args, const hand::HandSkin& skin,
                    const hand::HandShape& shape) {
  render::DrawList list;
  list.items.push_back(render::draw_task_scene({}, Eigen::Isometry3d::Identity()).items.front());
  const bool pair = args.flag("pair");
  render::draw_skin(list, skin.surface.vertices, skin.surface.triangles,
                    hand_placement(pair ? -0.13 : 0.0), {0.86f, 0.67f, 0.56f, 1.0f});
  if (pair) {
    hand::HandShape person = hand::HandShape::with_length(args.number("tracked-length"));
    person.left = shape.left;
    const hand::Skeleton tracked = hand::build_tracked_hand(person);
    render::draw_skeleton(list, tracked, hand::HandPose::rest(tracked), hand_placement(0.13),
                          {0.35f, 0.6f, 0.85f, 1.0f}, {0.95f, 0.95f, 0.95f, 1.0f});
  }
  render::write_png(render_hands(list, pair), args.text("png"));
}

void write_simulated_json(std::ostream& out, const hand::HandShape& shape,
                          const hand::Skeleton& skeleton, const hand::HandSkin& skin,
                          const std::optional<hand::HandFlesh>& flesh) {
  util::JsonWriter json(out);
  json.begin_object()
      .field("length_m", shape.length)
      .field("measured_length_m", skin.measured_length);
  json.field("bones", skeleton.bones.size()).field("dofs", skeleton.dofs.size());
  json.field("skin_vertices", skin.surface.vertices.size())
      .field("skin_triangles", skin.surface.triangles.size());
  if (flesh) {
    json.field("tets", flesh->quality.tets).field("nodes", flesh->tets.nodes.size());
    json.field("max_radius_edge_ratio", flesh->quality.max_radius_edge_ratio);
    json.field("min_dihedral_deg", flesh->quality.min_dihedral_deg);
    json.field("coupling_points", flesh->coupling.size());
  }
  json.end_object();
}

}  // namespace

int run_hand(const std::vector<std::string>& argv) {
  const Arguments args(hand_options(), argv);
  if (args.help_requested()) return print_help(hand_help(), args);
  hand::HandShape shape = hand::HandShape::with_length(args.number("length"));
  if (shape.length < 0.10 || shape.length > 0.30)
    throw UsageError("--length must be between 0.10 and 0.30 m");
  if (args.has("breadth")) shape.breadth = args.number("breadth");
  shape.left = args.flag("left");
  const long subdivisions = args.integer("subdivisions");
  if (subdivisions < 0 || subdivisions > 3) throw UsageError("--subdivisions must be 0 to 3");
  if (args.flag("tracked")) {
    show_tracked(args, shape);
    return 0;
  }
  const hand::Skeleton skeleton = hand::build_simulated_hand(shape);
  const hand::HandSkin skin = hand::build_skin(skeleton, shape, int(subdivisions));
  std::cout << "simulated hand: length " << shape.length * 100 << " cm (skin measures "
            << skin.measured_length * 100 << " cm), " << skeleton.bones.size() << " bones, "
            << skeleton.dofs.size() << " joint DOFs, skin " << skin.surface.vertices.size()
            << " vertices, " << skin.surface.triangles.size() << " triangles\n";
  if (args.has("out")) mesh::write_obj(skin.surface, args.text("out"));
  std::optional<hand::HandFlesh> flesh;
  if (args.has("tets")) flesh = write_flesh(args, skeleton, shape);
  if (args.has("png")) draw_simulated(args, skin, shape);
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_simulated_json(out, shape, skeleton, skin, flesh);
    });
  return 0;
}

}  // namespace handlab::cli
