// handlab-cli sim settle: the simulator's cube resting on the floor, kicked (a speed along the
// floor and a spin over its edges), then left alone: when it rests, how far it went and how
// high it rose, beside the furthest its starting energy could slide it (core/task/cube_settle.h).
// Without --speed and --spin, a grid of kicks such as fingers that let go give a light cube.
#include "app/cli/commands/sim_settle.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "analysis/stats/descriptives.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "core/task/cube_settle.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

const std::vector<double> kGridSpeeds = {0.02, 0.05, 0.1, 0.2, 0.4};                  // m/s
const std::vector<double> kGridSpins = {0.0, 1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0};  // rad/s

std::string listed(const std::vector<double>& values) {
  std::ostringstream out;
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
  return out.str();
}

struct Settings {
  sim::SimParameters parameters;
  sim::SimOptions options;
  double duration = 5.0;  // s
  std::vector<double> speeds = kGridSpeeds, spins = kGridSpins;
};

struct Row {
  sim::CubeKick kick;
  sim::CubeSettleReport report;
};

// Over the kicks: how many gained more than a tenth of their energy, the rest times' median
// and 90th percentile (-1 when one never came to rest) and the furthest beyond its energy's
// slide.
struct Summary {
  int gained = 0, never_at_rest = 0;
  double rest_median = 0.0, rest_p90 = 0.0, beyond = 0.0;  // s, s, m
};

Summary summarise(const std::vector<Row>& rows) {
  Summary s;
  std::vector<double> rest;
  s.beyond = -INFINITY;
  for (const Row& r : rows) {
    s.gained += r.report.highest_energy > 1.1 * r.report.start_energy;
    s.never_at_rest += r.report.rest_time < 0;
    rest.push_back(r.report.rest_time < 0 ? INFINITY : r.report.rest_time);
    s.beyond = std::max(s.beyond, r.report.travelled - r.report.slide_bound);
  }
  std::sort(rest.begin(), rest.end());
  s.rest_median = stats::quantile_type7(rest, 0.5);
  s.rest_p90 = stats::quantile_type7(rest, 0.9);
  return s;
}

Settings parse(const Arguments& args) {
  Settings s;
  sim::SimParameters& p = s.parameters;
  if (args.has("cube")) p.cube_size = args.number("cube");
  if (!(p.cube_size >= 0.005 && p.cube_size <= 0.1))
    throw UsageError("--cube must be between 0.005 and 0.1 m");
  if (args.has("time-step")) p.time_step = args.number("time-step");
  if (!(p.time_step >= 1e-5 && p.time_step <= 0.02))
    throw UsageError("--time-step must be 1e-5 to 0.02 s");
  if (args.has("floor-stiffness")) p.cube_floor_stiffness = args.number("floor-stiffness");
  if (args.has("floor-stiffening")) p.cube_floor_stiffening = args.number("floor-stiffening");
  if (!(p.cube_floor_stiffness > 0)) throw UsageError("--floor-stiffness must be > 0");
  if (!(p.cube_floor_stiffening >= 0)) throw UsageError("--floor-stiffening must be 0 or more");
  if (args.has("newton-iterations"))
    s.options.newton_iterations = int(args.integer("newton-iterations"));
  if (s.options.newton_iterations < 1 || s.options.newton_iterations > 20)
    throw UsageError("--newton-iterations must be 1 to 20");
  if (args.has("duration")) s.duration = args.number("duration");
  if (!(s.duration >= 0.1 && s.duration <= 60)) throw UsageError("--duration must be 0.1 to 60 s");
  if (args.has("speed")) s.speeds = {args.number("speed")};
  if (args.has("spin")) s.spins = {args.number("spin")};
  for (double v : s.speeds)
    if (!(v >= 0 && v <= 5)) throw UsageError("--speed must be 0 to 5 m/s");
  for (double w : s.spins)
    if (!(w >= 0 && w <= 100)) throw UsageError("--spin must be 0 to 100 rad/s");
  if (s.speeds.size() == 1 && s.spins.size() == 1 && s.speeds[0] == 0 && s.spins[0] == 0)
    throw UsageError("a kick needs a speed or a spin");
  return s;
}

void print_table(const Settings& s, const std::vector<Row>& rows, const Summary& sum) {
  const sim::SimParameters& p = s.parameters;
  std::cout << "cube " << p.cube_size * 100 << " cm; a corner on the floor "
            << p.cube_floor_stiffness << " N/m + " << p.cube_floor_stiffening
            << " N/m^2 x depth; step " << p.time_step * 1000 << " ms, "
            << s.options.newton_iterations << " Newton iteration(s)\n\n"
            << "speed m/s  spin rad/s  at rest s  travelled mm  energy allows mm  rise mm  "
               "energy peak / start\n"
            << std::fixed;
  for (const Row& r : rows) {
    const sim::CubeSettleReport& x = r.report;
    std::cout << std::setprecision(2) << std::setw(9) << r.kick.speed << std::setw(12)
              << r.kick.spin << std::setw(11);
    if (x.rest_time < 0)
      std::cout << "never";
    else
      std::cout << x.rest_time;
    std::cout << std::setw(14) << x.travelled * 1000 << std::setw(18) << x.slide_bound * 1000
              << std::setw(9) << x.highest_rise * 1000 << std::setw(21)
              << x.highest_energy / x.start_energy << "\n";
  }
  if (rows.size() < 2) return;
  std::cout << "\n"
            << rows.size() << " kicks: " << sum.gained
            << " gained more than a tenth of their energy; at rest after ";
  if (sum.never_at_rest > 0) std::cout << "(" << sum.never_at_rest << " never) ";
  std::cout << sum.rest_median << " s median, " << sum.rest_p90 << " s p90; at most "
            << sum.beyond * 1000 << " mm beyond what their energy allows\n";
}

void write_json(std::ostream& out, const Settings& s, const std::vector<Row>& rows,
                const Summary& sum) {
  const sim::SimParameters& p = s.parameters;
  util::JsonWriter json(out);
  auto seconds = [&](double t) -> util::JsonWriter& {
    return t < 0 || !std::isfinite(t) ? json.null() : json.value(t);
  };
  json.begin_object()
      .field("cube_m", p.cube_size)
      .field("floor_stiffness_n_m", p.cube_floor_stiffness)
      .field("floor_stiffening_n_m2", p.cube_floor_stiffening)
      .field("time_step_s", p.time_step)
      .field("newton_iterations", s.options.newton_iterations)
      .field("duration_s", s.duration)
      .field("kicks_gaining_energy", sum.gained)
      .field("kicks_never_at_rest", sum.never_at_rest)
      .key("rest_time_median_s");
  seconds(sum.rest_median).key("rest_time_p90_s");
  seconds(sum.rest_p90).field("most_beyond_slide_bound_m", sum.beyond).key("kicks").begin_array();
  for (const Row& r : rows) {
    json.begin_object()
        .field("speed_m_s", r.kick.speed)
        .field("spin_rad_s", r.kick.spin)
        .key("rest_time_s");
    seconds(r.report.rest_time)
        .field("travelled_m", r.report.travelled)
        .field("slide_bound_m", r.report.slide_bound)
        .field("highest_rise_m", r.report.highest_rise)
        .field("start_energy_j", r.report.start_energy)
        .field("highest_energy_j", r.report.highest_energy)
        .end_object();
  }
  json.end_array().end_object();
}

}  // namespace

std::vector<OptionSpec> sim_settle_options() {
  return {
      {"cube", "SIDE", "the cube's side (m; default: the study's fine cube, 0.01)"},
      {"speed", "M/S", "one kick's speed along the floor (default: " + listed(kGridSpeeds) + ")"},
      {"spin", "RAD/S", "one kick's backspin over its edges (default: " + listed(kGridSpins) + ")"},
      {"duration", "SECONDS", "how long after the kick it is followed (default 5)"},
      {"newton-iterations", "N", "Newton iterations a step (default: the simulator's, 1)"},
      {"time-step", "SECONDS", "the simulator's step (default: the study's, 1/120 s)"},
      {"floor-stiffness", "N/M",
       "k of a corner's force on the floor, k d + k3 d^2 (default: the simulator's)"},
      {"floor-stiffening", "N/M2", "k3 (default: the simulator's)"},
      {"json", "OUT", "write the result as JSON (- for standard output)"},
  };
}

CommandHelp sim_settle_help() {
  return {"sim settle",
          {"[cube] [speed] [spin] [json] [options]"},
          "Kicks the simulator's cube resting on the floor and follows it alone: when it comes "
          "to rest\n"
          "(within 0.1 mm and 0.01 rad of where it ends, from then on), how far it went, how "
          "high its\n"
          "centre rose and its most energy, beside the furthest its starting energy could slide "
          "it\n"
          "(E0 / (mu m g))."};
}

int sim_settle(const std::vector<std::string>& argv) {
  const Arguments args(sim_settle_options(), argv);
  if (args.help_requested()) return print_help(sim_settle_help(), args);
  const Settings settings = parse(args);
  std::vector<Row> rows;
  for (double v : settings.speeds)
    for (double w : settings.spins)
      if (v > 0 || w > 0)
        rows.push_back(
            {{v, w},
             sim::settle_cube(settings.parameters, {v, w}, settings.options, settings.duration)});
  const Summary summary = summarise(rows);
  const std::string json_out = args.text("json");
  if (json_out != "-") print_table(settings, rows, summary);
  if (args.has("json"))
    util::write_output(json_out,
                       [&](std::ostream& out) { write_json(out, settings, rows, summary); });
  return 0;
}

}  // namespace handlab::cli
