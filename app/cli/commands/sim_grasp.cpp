// handlab-cli sim grasp: the pinch-lift-hold-release of each cube over a grid of closings,
// each factor alone from the scripted pinch: which closings the soft hand's grip holds.
#include "app/cli/commands/sim_grasp.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/cli/arguments.h"
#include "app/cli/progress_line.h"
#include "core/task/grasp_map.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

double number_option(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw UsageError(what + " needs a number, not '" + text + "'");
  return value;
}

// --closing over_closure=10,lead=100: one closing, in the factors' units.
sim::ClosingPoint parse_closing(const std::string& text) {
  sim::ClosingPoint point{"closing", 0.0, {}};
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw UsageError("--closing takes NAME=VALUE,..., not '" + item + "'");
    try {
      sim::set_closing_factor(
          point.closing, item.substr(0, eq),
          number_option(item.substr(eq + 1), "--closing " + item.substr(0, eq)));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--closing: ") + e.what());
    }
  }
  return point;
}

struct CubeMap {
  double cube_size = 0.0;
  std::vector<sim::GraspOutcome> outcomes;
};

void print_map(const CubeMap& map) {
  std::printf("\ncube %.0f mm\n%-14s %8s %-5s  %-4s %-8s %8s %9s\n", map.cube_size * 1000, "factor",
              "level", "unit", "held", "released", "slip mm", "deepest mm");
  std::map<std::string, std::pair<int, int>> held;  // factor -> held, run
  for (const sim::GraspOutcome& o : map.outcomes) {
    const std::string unit = o.point.factor.empty() || o.point.factor == "closing"
                                 ? ""
                                 : sim::closing_factor(o.point.factor).unit;
    std::printf("%-14s %8g %-5s  %-4s %-8s %8.3f %9.2f\n",
                o.point.factor.empty() ? "scripted" : o.point.factor.c_str(), o.point.level,
                unit.c_str(), o.held ? "yes" : "NO", o.released ? "yes" : "NO", o.slip_mm,
                o.max_penetration_mm);
    auto& [h, n] = held[o.point.factor.empty() ? "scripted" : o.point.factor];
    h += o.held ? 1 : 0;
    ++n;
  }
  std::printf("held:");
  for (const auto& [factor, count] : held)
    std::printf(" %s %d of %d;", factor.c_str(), count.first, count.second);
  std::printf("\n");
}

void write_map_json(const std::vector<CubeMap>& maps, std::ostream& out) {
  util::JsonWriter json(out);
  json.begin_object().key("factors").begin_array();
  for (const sim::ClosingFactor& f : sim::closing_factors()) {
    json.begin_object().field("name", f.name).field("unit", f.unit).key("levels").begin_array();
    for (double level : f.levels) json.value(level);
    json.end_array().end_object();
  }
  json.end_array().key("cubes").begin_array();
  for (const CubeMap& map : maps) {
    json.begin_object().field("cube_size_m", map.cube_size).key("closings").begin_array();
    for (const sim::GraspOutcome& o : map.outcomes)
      json.begin_object()
          .field("factor", o.point.factor)
          .field("level", o.point.level)
          .field("closing", sim::describe(o.point.closing))
          .field("held", o.held)
          .field("released", o.released)
          .field("lift_m", o.lift_m)
          .field("slip_mm", o.slip_mm)
          .field("max_penetration_mm", o.max_penetration_mm)
          .field("pinch_error_mm", o.pinch_error_mm)
          .end_object();
    int held = 0;
    for (const sim::GraspOutcome& o : map.outcomes) held += o.held ? 1 : 0;
    json.end_array()
        .field("held", held)
        .field("closings_run", int(map.outcomes.size()))
        .end_object();
  }
  json.end_array().end_object();
  out << "\n";
}

}  // namespace

int sim_grasp(const std::vector<std::string>& argv) {
  const std::vector<OptionSpec> specs = {
      {"cube", "METRES", "a cube's side; repeatable (default: 0.01 and 0.06, the study's)", "",
       true},
      {"factor", "NAME",
       "map only this factor of the closing; repeatable (default: every one: over_closure, "
       "tilt_yaw, tilt_pitch, offset_along, lead, closing_speed, hold)",
       "", true},
      {"closing", "NAME=VALUE,...",
       "run this one closing instead of the grid, in the factors' units (mm, deg, side, ms, "
       "cm/s, s), e.g. over_closure=20,lead=100"},
      {"jobs", "J", "closings run side by side (default: the machine's cores)", "0"},
      {"json", "OUT", "write every closing's outcome as JSON (- for standard output)"},
  };
  const Arguments args(specs, argv);
  if (args.help_requested()) {
    std::cout << "Usage: handlab-cli sim grasp [--cube SIDE]... [--factor NAME]... [--closing "
                 "NAME=VALUE,...] [--jobs J] [--json OUT]\n\n"
                 "The soft hand pinches each cube, lifts it 10 cm, holds it and opens, closing "
                 "as the closing says on the intermediate hand it follows: each pad's target "
                 "past its face (over_closure, mm), the pinch's axis turned about the vertical "
                 "and the faces' horizontal (tilt_yaw, tilt_pitch, degrees), the pads moved "
                 "along the faces (offset_along, of the side), one digit first (lead, ms: the "
                 "thumb before the index; below 0 after), the closing's speed (closing_speed, "
                 "cm/s of each pad) and the hold (hold, s). The grid runs each factor alone at "
                 "its levels from the scripted pinch (sim pinch). Reports per closing whether "
                 "the cube was held through the lift and hold and released, its slip between "
                 "the pads and the flesh's deepest penetration; the hold rate per factor "
                 "(docs/simulator.md).\n\nOptions:\n"
              << format_options_help(specs);
    return 0;
  }
  std::vector<double> cubes;
  for (const std::string& c : args.all("cube")) {
    const double side = number_option(c, "--cube");
    if (!(side >= 0.005 && side <= 0.1))
      throw UsageError("--cube must be between 0.005 and 0.1 m, not " + c);
    cubes.push_back(side);
  }
  if (cubes.empty()) cubes = {0.01, 0.06};
  std::vector<sim::ClosingPoint> points;
  if (args.has("closing")) {
    if (args.has("factor")) throw UsageError("give --closing or --factor, not both");
    points = {parse_closing(args.text("closing"))};
  } else {
    try {
      for (const std::string& f : args.all("factor")) sim::closing_factor(f);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--factor: ") + e.what());
    }
    points = sim::single_factor_grid(args.all("factor"));
  }
  int jobs = int(args.integer("jobs"));
  if (jobs < 0) throw UsageError("--jobs must be 0 (all cores) or more");
  if (jobs == 0) jobs = int(std::max(1u, std::thread::hardware_concurrency()));
  const bool to_stdout = args.text("json") == "-";
  std::vector<CubeMap> maps;
  const auto start = std::chrono::steady_clock::now();
  for (double side : cubes) {
    const sim::PinchScene scene = sim::make_pinch_scene(side);
    ProgressLine progress(to_stdout);
    CubeMap map;
    map.cube_size = side;
    map.outcomes = sim::run_grasp_map(scene, points, jobs, [&](int done) {
      char text[120];
      std::snprintf(
          text, sizeof text, "cube %.0f mm: closings %d/%zu  %.0f s", side * 1000, done,
          points.size(),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      progress.show(done, text);
    });
    progress.finish();
    if (!to_stdout) print_map(map);
    maps.push_back(std::move(map));
  }
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) { write_map_json(maps, out); });
  return 0;
}

}  // namespace handlab::cli
