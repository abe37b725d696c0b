// handlab-cli sim: the soft-hand simulator on its scripted pinch-and-lift. `bench` measures the
// step time (the study mesh, or 4x and 16x finer ones); `pinch` runs the whole script and says
// whether the cube was held, how far it slipped and how deep the flesh went into it; `replay`
// (sim_replay.cpp) drives the hand by a real recording; `settle` (sim_settle.cpp) kicks the cube
// alone on the floor.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "analysis/stats/descriptives.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/commands/sim_grasp.h"
#include "app/cli/commands/sim_pinches.h"
#include "app/cli/commands/sim_replay.h"
#include "app/cli/commands/sim_settle.h"
#include "app/cli/commands/step_parts.h"
#include "core/hand/flesh.h"
#include "core/hand/hand_shape.h"
#include "core/hand/simulated_hand.h"
#include "core/render/hand_drawing.h"
#include "core/render/offscreen_context.h"
#include "core/render/sim_drawing.h"
#include "core/sim/contact_forces.h"
#include "core/sim/sim_options.h"
#include "core/task/pinch_scene.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

using stats::timing_quantile;

template <typename T>
double mean(const std::vector<T>& values) {
  return values.empty()
             ? 0.0
             : double(std::accumulate(values.begin(), values.end(), T(0))) / double(values.size());
}

double cube_option(const Arguments& args) {
  const double cube = args.number("cube");
  if (!(cube >= 0.005 && cube <= 0.1)) throw UsageError("--cube must be between 0.005 and 0.1 m");
  return cube;
}

sim::SimParameters simulator_parameters(const Arguments& args) {
  sim::SimParameters p;
  p.skin_samples = int(args.integer("skin-samples"));
  if (p.skin_samples != 0 && p.skin_samples != 1) throw UsageError("--skin-samples must be 0 or 1");
  return p;
}

// The script's phases and the steps each took (a step belongs to the phase its end time is in).
struct Phase {
  const char* name = "";
  double from = 0.0, to = 0.0;  // s
  std::vector<double> ms;
  double linear = 0.0, passes = 0.0;
  int factorizations = 0;
};

std::vector<Phase> phases(const sim::PinchScene& setup, const sim::PinchReport& r) {
  const sim::PinchScript& s = setup.script;
  const std::vector<std::pair<const char*, double>> ends = {
      {"shape", s.shape_end},  {"approach", s.approach_end},
      {"close", s.close_end},  {"settle", s.lift_start},
      {"lift", s.lift_end},    {"hold", s.hold_end},
      {"open", s.release_end}, {"fall", s.end}};
  std::vector<Phase> list;
  double from = 0.0;
  for (const auto& [name, to] : ends) {
    Phase p;
    p.name = name;
    p.from = from;
    p.to = to;
    list.push_back(std::move(p));
    from = to;
  }
  const double h = setup.model.parameters.time_step;
  for (std::size_t i = 0; i < r.step_ms.size(); ++i) {
    const double t = double(i + 1) * h;
    for (Phase& p : list)
      if (t > p.from + 1e-9 && t <= p.to + 1e-9) {
        p.ms.push_back(r.step_ms[i]);
        p.linear += r.linear_iterations[i];
        p.passes += r.newton_iterations[i];
        p.factorizations += r.factorizations[i];
      }
  }
  std::vector<Phase> taken;
  for (Phase& p : list)
    if (!p.ms.empty()) {
      p.linear /= double(p.ms.size());
      p.passes /= double(p.ms.size());
      taken.push_back(std::move(p));
    }
  return taken;
}

// Where the steps' time went: each timer's mean a step, and the rest (the step's time less its
// timers), over every step and over the slowest (at or above the p99).
struct TimerMeans {
  std::size_t slowest_steps = 0;
  std::array<double, sim::kStepTimers + 1> all{}, slowest{};  // the rest last
};

TimerMeans timer_means(const sim::PinchReport& r) {
  TimerMeans means;
  const double p99 = timing_quantile(r.step_ms, 0.99);
  for (std::size_t i = 0; i < r.step_ms.size(); ++i) {
    std::array<double, sim::kStepTimers + 1> parts{};
    double timed = 0.0;
    for (std::size_t k = 0; k < sim::kStepTimers; ++k) timed += parts[k] = r.timer_ms[i][k];
    parts.back() = std::max(0.0, r.step_ms[i] - timed);
    const bool slow = r.step_ms[i] >= p99;
    means.slowest_steps += slow;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      means.all[k] += parts[k];
      if (slow) means.slowest[k] += parts[k];
    }
  }
  for (std::size_t k = 0; k < means.all.size(); ++k) {
    means.all[k] /= double(std::max<std::size_t>(1, r.step_ms.size()));
    means.slowest[k] /= double(std::max<std::size_t>(1, means.slowest_steps));
  }
  return means;
}

void write_timing(util::JsonWriter& json, const sim::PinchScene& setup, const sim::PinchReport& r) {
  const std::vector<int>& lin = r.linear_iterations;
  json.field("tets", setup.model.tets.size())
      .field("nodes", setup.model.node_count())
      .field("bones", setup.model.bone_count())
      .field("dofs", setup.model.dof_count())
      .field("steps", r.step_ms.size())
      .field("time_step_s", setup.model.parameters.time_step);
  json.key("step_ms")
      .begin_object()
      .field("median", timing_quantile(r.step_ms, 0.5))
      .field("p95", timing_quantile(r.step_ms, 0.95))
      .field("p99", timing_quantile(r.step_ms, 0.99))
      .field("max", timing_quantile(r.step_ms, 1.0))
      .field("mean", mean(r.step_ms))
      .end_object();
  json.key("newton_iterations")
      .begin_object()
      .field("mean", mean(r.newton_iterations))
      .field("max", *std::max_element(r.newton_iterations.begin(), r.newton_iterations.end()))
      .end_object();
  json.key("linear_iterations")
      .begin_object()
      .field("mean", mean(lin))
      .field("max", *std::max_element(lin.begin(), lin.end()))
      .end_object();
  json.field("factorizations",
             std::accumulate(r.factorizations.begin(), r.factorizations.end(), 0));
  json.field("direct_solves", std::accumulate(r.direct_solves.begin(), r.direct_solves.end(), 0));
  json.field("failed_cg", std::accumulate(r.failed_cg.begin(), r.failed_cg.end(), 0));
  json.key("phases").begin_array();
  for (const Phase& p : phases(setup, r))
    json.begin_object()
        .field("name", p.name)
        .field("from_s", p.from)
        .field("to_s", p.to)
        .field("steps", p.ms.size())
        .field("median_ms", timing_quantile(p.ms, 0.5))
        .field("p95_ms", timing_quantile(p.ms, 0.95))
        .field("newton_iterations_mean", p.passes)
        .field("linear_iterations_mean", p.linear)
        .field("factorizations", p.factorizations)
        .end_object();
  json.end_array();
  const TimerMeans means = timer_means(r);
  json.key("timers").begin_object().field("slowest_steps", means.slowest_steps);
  json.key("parts").begin_array();
  for (std::size_t k = 0; k < means.all.size(); ++k)
    json.begin_object()
        .field("name", step_part_name(k))
        .field("mean_ms", means.all[k])
        .field("slowest_mean_ms", means.slowest[k])
        .end_object();
  json.end_array().end_object();
}

void print_timing(const sim::PinchScene& setup, const sim::PinchReport& r) {
  std::cout << std::fixed << std::setprecision(2) << setup.model.tets.size() << " tets, "
            << setup.model.node_count() << " nodes, " << setup.model.bone_count() << " bones, "
            << setup.model.dof_count() << " DOFs; " << r.step_ms.size() << " steps: median "
            << timing_quantile(r.step_ms, 0.5) << " ms, p95 " << timing_quantile(r.step_ms, 0.95)
            << " ms, p99 " << timing_quantile(r.step_ms, 0.99) << " ms, max "
            << timing_quantile(r.step_ms, 1.0) << " ms; Newton " << mean(r.newton_iterations)
            << ", CG " << mean(r.linear_iterations) << " a step, "
            << std::accumulate(r.factorizations.begin(), r.factorizations.end(), 0)
            << " factorisations (" << std::accumulate(r.failed_cg.begin(), r.failed_cg.end(), 0)
            << " after a CG that failed)\n";
  for (const Phase& p : phases(setup, r))
    std::cout << "  " << std::left << std::setw(9) << p.name << std::right << std::setw(4)
              << p.ms.size() << " steps: median " << timing_quantile(p.ms, 0.5) << " ms, p95 "
              << timing_quantile(p.ms, 0.95) << " ms; Newton " << p.passes << ", CG " << p.linear
              << " a step, " << p.factorizations << " factorisations\n";
  const TimerMeans means = timer_means(r);
  std::cout << "  ms a step, all steps / the " << means.slowest_steps << " at the p99 or over:";
  for (std::size_t k = 0; k < means.all.size(); ++k)
    std::cout << (k ? ", " : " ") << step_part_label(k) << ' ' << means.all[k] << " / "
              << means.slowest[k];
  std::cout << '\n';
}

// The solver's settings from --newton-iterations ... --threads, checked.
sim::SimOptions solver_options(const Arguments& args) {
  sim::SimOptions options;
  options.newton_iterations = int(args.integer("newton-iterations"));
  options.refactor_iterations = int(args.integer("refactor-iterations"));
  if (options.newton_iterations < 1 || options.newton_iterations > 20)
    throw UsageError("--newton-iterations must be 1 to 20");
  if (options.refactor_iterations < 0) throw UsageError("--refactor-iterations must be >= 0");
  options.linear_tolerance = args.number("linear-tolerance");
  if (!(options.linear_tolerance > 0 && options.linear_tolerance < 1e-3))
    throw UsageError("--linear-tolerance must be in (0, 1e-3) m");
  options.max_linear_iterations = int(args.integer("max-linear-iterations"));
  if (options.max_linear_iterations < 0) throw UsageError("--max-linear-iterations must be >= 0");
  options.direct_steps = int(args.integer("direct-steps"));
  if (options.direct_steps < 0) throw UsageError("--direct-steps must be >= 0");
  options.refresh_steps = int(args.integer("refresh-steps"));
  if (options.refresh_steps < 0) throw UsageError("--refresh-steps must be >= 0");
  options.halfway_gap = args.number("halfway-gap");
  if (!(options.halfway_gap >= 0)) throw UsageError("--halfway-gap must be >= 0");
  options.threads = int(args.integer("threads"));
  if (options.threads < 1 || options.threads > 64) throw UsageError("--threads must be 1 to 64");
  return options;
}

// --steps: every step's time and solver counts.
void write_steps_csv(std::ostream& out, double time_step, const sim::PinchReport& report) {
  out << "step,time_s,step_ms,newton_iterations,linear_iterations,factorizations,contacts,"
         "halvings,direct_solves,failed_cg";
  for (const char* name : sim::kStepTimerNames) out << ',' << name << "_ms";
  out << '\n';
  for (std::size_t i = 0; i < report.step_ms.size(); ++i) {
    out << i << ',' << double(i + 1) * time_step << ',' << report.step_ms[i] << ','
        << report.newton_iterations[i] << ',' << report.linear_iterations[i] << ','
        << report.factorizations[i] << ',' << report.contacts[i] << ',' << report.halvings[i] << ','
        << report.direct_solves[i] << ',' << report.failed_cg[i];
    for (double ms : report.timer_ms[i]) out << ',' << ms;
    out << '\n';
  }
}

std::vector<OptionSpec> sim_bench_options() {
  return {
      {"scale", "N", "the flesh mesh: 1 (the study's), 4 or 16 times more tets", "1"},
      {"cube", "METRES", "the cube's side", "0.01"},
      {"duration", "SECONDS", "how much of the script to run (default: to 0.5 s after the lift)"},
      {"newton-iterations", "N", "Newton iterations a step", "1"},
      {"refactor-iterations", "N",
       "factorise the matrix anew after a solve that needed more CG iterations than this", "4"},
      {"linear-tolerance", "METRES",
       "CG stops when the residual left would move no unknown by more than this", "1e-8"},
      {"max-linear-iterations", "N",
       "CG iterations before the matrix is factorised anew and solved directly", "6"},
      {"direct-steps", "N",
       "after CG failed with the previous step's factorisation, steps that factorise at once", "3"},
      {"refresh-steps", "N",
       "factorise after this many steps in a row needed two CG iterations or more (0: never)",
       "20"},
      {"halfway-gap", "RATIO",
       "CG gives up halfway when the residual left would still move an unknown by more than "
       "this many times the linear tolerance (0: never)",
       "1000"},
      {"skin-samples", "N",
       "contact points against the cube inside each of the flesh's boundary faces besides its "
       "nodes: 1 (the centroid) or 0 (the nodes alone, as before 2026-11-26)",
       "1"},
      {"threads", "N", "threads the per-tet work is split over", "2"},
      {"runs", "N",
       "run the script N times and time each step by its fastest run (the machine's other load "
       "only adds time; the runs must agree step by step)",
       "1"},
      {"json", "OUT", "write the figures as JSON (- for standard output)"},
      {"steps", "CSV",
       "write every step's time (ms), Newton and CG iterations, factorisations, contacts, "
       "line-search halvings, direct solves, CG solves that failed, and the time of each part of "
       "its solve (ms: " +
           step_part_names() + ")"},
      physics_option(),
      posture_option(),
  };
}

CommandHelp sim_bench_help() {
  return {"sim bench",
          {"[scale] [cube] [physics] [posture] [json] [options]"},
          "Times the simulator's steps on the scripted pinch-and-lift of the cube (come down, "
          "close thumb\n"
          "and index, lift 10 cm)."};
}

int sim_bench(const std::vector<std::string>& argv) {
  const Arguments args(sim_bench_options(), argv);
  if (args.help_requested()) return print_help(sim_bench_help(), args);
  const long scale = args.integer("scale");
  if (scale != 1 && scale != 4 && scale != 16) throw UsageError("--scale must be 1, 4 or 16");
  sim::SimParameters parameters = simulator_parameters(args);
  apply_physics_option(args, parameters);
  const sim::PinchScene setup = sim::make_pinch_scene(
      cube_option(args), int(scale), 0.003, hand::HandShape{}.length, parameters, posture_of(args));
  const double duration =
      args.has("duration") ? args.number("duration") : setup.script.lift_end + 0.5;
  if (!(duration > 0 && duration <= 60)) throw UsageError("--duration must be in (0, 60] s");
  const sim::SimOptions options = solver_options(args);
  const long runs = args.integer("runs");
  if (runs < 1 || runs > 50) throw UsageError("--runs must be 1 to 50");
  sim::PinchReport report =
      sim::run_pinch(setup.model, setup.skeleton, setup.script, options, duration);
  for (long run = 1; run < runs; ++run) {
    const sim::PinchReport again =
        sim::run_pinch(setup.model, setup.skeleton, setup.script, options, duration);
    if (again.linear_iterations != report.linear_iterations ||
        again.factorizations != report.factorizations)
      throw std::runtime_error("sim bench: run " + std::to_string(run + 1) +
                               " took other iterations than the first");
    for (std::size_t i = 0; i < report.step_ms.size(); ++i)
      if (again.step_ms[i] < report.step_ms[i]) {
        report.step_ms[i] = again.step_ms[i];
        report.timer_ms[i] = again.timer_ms[i];  // the parts of the run that counts
      }
  }
  if (args.text("json") != "-") {  // else the JSON alone
    // What was timed, when it is not the default pinch.
    if (args.has("posture") || args.has("physics")) {
      std::cout << sim::pinch_posture_name(setup.script.posture) << " posture";
      for (const std::string& item : args.all("physics")) std::cout << ", " << item;
      std::cout << '\n';
    }
    print_timing(setup, report);
  }
  if (args.has("steps"))
    util::write_output(args.text("steps"), [&](std::ostream& out) {
      write_steps_csv(out, setup.model.parameters.time_step, report);
    });
  if (args.has("json")) {
    util::write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter json(out);
      json.begin_object().field("scale", int(scale)).field("cube_size_m", setup.script.cube_size);
      json.field("duration_s", duration).field("threads", options.threads).field("runs", int(runs));
      json.field("posture", sim::pinch_posture_name(setup.script.posture));
      json.field("direct_steps", options.direct_steps)
          .field("refresh_steps", options.refresh_steps)
          .field("halfway_gap", options.halfway_gap);
      write_physics(json, args.all("physics"));
      write_timing(json, setup, report);
      json.end_object();
    });
  }
  return 0;
}

// Frames of the run, seen from the thumb's side and a little above.
class FrameWriter {
 public:
  FrameWriter(const sim::PinchScene& setup, std::filesystem::path directory, double interval,
              double yaw, bool contacts)
      : setup_(setup),
        directory_(std::move(directory)),
        interval_(interval),
        contacts_(contacts),
        renderer_(640, 480) {
    std::filesystem::create_directories(directory_);
    camera_.distance = float(0.3 + 2 * setup.script.cube_size);
    camera_.yaw = float(yaw);
    camera_.pitch = 0.25f;
  }
  void operator()(const sim::HandSimState& state) {
    if (state.time + 1e-9 < next_) return;
    next_ += interval_;
    // The camera follows the cube across the floor, looking at half the lift's height.
    camera_.target = Eigen::Vector3f(float(state.cube_pose.position.x()),
                                     float(setup_.script.cube_centre.y() + 0.05),
                                     float(state.cube_pose.position.z()));
    task::SceneLayout layout;
    layout.cube_size = setup_.script.cube_size;
    layout.zone_a = Eigen::Vector3d(0.3, 0, 0);  // out of the picture
    layout.zone_b = Eigen::Vector3d(0.6, 0, 0);
    render::SimDrawStyle style;
    style.contacts = contacts_;
    const render::DrawList list =
        render::draw_sim_state(layout, setup_.flesh, setup_.model, state, style);
    std::ostringstream name;
    name << "frame_" << std::setw(3) << std::setfill('0') << count_++ << ".png";
    render::write_png(renderer_.render(list, camera_), (directory_ / name.str()).string());
  }

 private:
  const sim::PinchScene& setup_;
  std::filesystem::path directory_;
  double interval_, next_ = 0.0;
  bool contacts_;
  int count_ = 0;
  render::OffscreenRenderer renderer_;
  render::OrbitCamera camera_;
};

// --trace: a step's row.
void write_trace_row(std::ostream& trace, const sim::PinchScene& setup,
                     const sim::HandSimState& s) {
  trace << s.time << ',' << s.cube_pose.position.y() << ',' << sim::cube_turn_deg(s) << ','
        << sim::grip_force(setup.model, s) << ','
        << sim::flesh_forces_on_cube_faces(setup.model, s)[3] << ','  // its own +y: the top
        << s.node_cube.size() + s.sample_cube.size();
  const std::vector<sim::RigidPose> targets =
      sim::bone_targets(setup.model, setup.skeleton, setup.script.target(s.time));
  double offset = 0, turn = 0;  // the bones' largest from their targets
  std::size_t farthest = 0;
  for (std::size_t b = 0; b < targets.size(); ++b) {
    const double away = (s.bone_pose[b].position - targets[b].position).norm();
    if (away > offset) offset = away, farthest = b;
    turn = std::max(turn, s.bone_pose[b].rotation.angularDistance(targets[b].rotation));
  }
  trace << ',' << offset * 1000 << ',' << turn * 180 / M_PI << ','
        << setup.skeleton.bones[farthest].name << '\n';
}

void print_pinch(const sim::PinchScene& setup, const sim::PinchReport& r) {
  std::cout << std::fixed << std::setprecision(3) << "cube " << setup.script.cube_size * 100
            << " cm: " << (r.held ? "held" : "NOT held") << ", lifted " << r.lift * 100
            << " cm, slip " << r.slip_mm << " mm, max penetration " << r.max_penetration_mm
            << " mm, peak grip " << r.peak_grip_n << " N, turned " << r.turn_deg << " deg, top "
            << r.top_load_before_closing_n << " N before the closing, " << r.inverted_tets
            << " tets inside out at most, " << (r.released ? "released" : "NOT released")
            << " (the scripted pads miss their "
            << "targets by " << setup.script.pinch_error * 1000 << " mm"
            << (setup.script.placed_by_rule ? "; the hand placed by the pinch's rule" : "")
            << (setup.script.posture == sim::PinchPosture::kFunctional
                    ? "; in the functional posture"
                    : "")
            << ")\n";
  print_timing(setup, r);
}

void write_pinch_json(std::ostream& out, const sim::PinchScene& setup,
                      const sim::SimOptions& options, const sim::PinchReport& r) {
  util::JsonWriter json(out);
  json.begin_object()
      .field("cube_size_m", setup.script.cube_size)
      .field("newton_iterations_a_pass", options.newton_iterations)
      .field("posture", sim::pinch_posture_name(setup.script.posture))
      .field("placed_by_rule", setup.script.placed_by_rule)
      .field("meets_pinch_rule", setup.script.pinch_meets_rule)
      .field("pinch_clearance_mm", 1000 * setup.script.pinch_clearance)
      .field("placement_pad_error_mm", 1000 * setup.script.placement_pad_error)
      .field("open_clearance_mm", 1000 * setup.script.open_clearance);
  write_pinch_measures(json, r);
  write_timing(json, setup, r);
  json.end_object();
}

std::vector<OptionSpec> sim_pinch_options() {
  std::vector<OptionSpec> specs = {
      {"cube", "METRES", "the cube's side (the study: 0.01 fine, 0.06 gross)", "0.01"},
      {"squeeze", "METRES", "how far inside the faces the pads' targets are", "0.003"},
      {"closing", "NAME=VALUE,...",
       "close as this closing of sim grasp says (its factors in their units, e.g. "
       "over_closure=20,tilt_pitch=10) instead of the scripted pinch"},
      {"jitter-from", "RECORDING",
       "with --closing jitter=X: the recording whose jitter it lays on"},
      {"frames", "DIR", "draw the run offscreen into DIR/frame_NNN.png"},
      {"frame-interval", "SECONDS", "with --frames: time between frames", "0.25"},
      {"view-yaw", "RAD", "with --frames: the camera's turn about the vertical", "-0.8"},
      {"contacts", "", "with --frames: draw the contact points"},
      {"trace", "CSV",
       "write every step's time, the cube's height and turn, the grip, the flesh's force on the "
       "cube's face that is its top at the start, the flesh points on the cube, and the bones' "
       "largest offset and turn from "
       "their targets with the bone farthest off (- for standard output)"},
      {"skin-samples", "N",
       "contact points against the cube inside each of the flesh's boundary faces besides its "
       "nodes: 1 (the centroid) or 0 (the nodes alone, as before 2026-11-26)",
       "1"},
      {"newton-iterations", "N",
       "Newton iterations a step (more: whether an outcome is the physics' or the one-iteration "
       "scheme's)",
       "1"},
      {"json", "OUT", "write the result as JSON (- for standard output)"},
  };
  specs.push_back(physics_option());
  specs.push_back(posture_option());
  return specs;
}

CommandHelp sim_pinch_help() {
  return {"sim pinch",
          {"[cube] [squeeze] [frames] [trace] [physics] [posture] [json] [options]",
           "[cube] closing [jitter-from] [frames] [trace] [physics] [posture] [json] [options]"},
          "Pinches the cube between thumb and index, lifts it 10 cm, holds it 5 s and opens the "
          "fingers.\n"
          "Reports whether it was held, its slip between the pads, the flesh's deepest "
          "penetration, the hold's peak grip and the cube's turn."};
}

int sim_pinch(const std::vector<std::string>& argv) {
  const Arguments args(sim_pinch_options(), argv);
  if (args.help_requested()) return print_help(sim_pinch_help(), args);
  const double squeeze = args.number("squeeze");
  if (!(squeeze >= 0 && squeeze <= 0.005)) throw UsageError("--squeeze must be 0 to 0.005 m");
  sim::SimOptions options;
  options.newton_iterations = int(args.integer("newton-iterations"));
  if (options.newton_iterations < 1 || options.newton_iterations > 20)
    throw UsageError("--newton-iterations must be 1 to 20");
  sim::SimParameters parameters = simulator_parameters(args);
  apply_physics_option(args, parameters);
  const sim::PinchPosture posture = posture_of(args);
  sim::PinchScene setup = sim::make_pinch_scene(cube_option(args), 1, squeeze,
                                                hand::HandShape{}.length, parameters, posture);
  if (args.text("trace") == "-" && args.text("json") == "-")
    throw UsageError("--trace - and --json - would share standard output: give one a file");
  if (args.has("jitter-from") && !args.has("closing"))
    throw UsageError("--jitter-from lays its jitter on a --closing with jitter=X");
  if (args.has("closing")) {
    if (args.has("squeeze")) throw UsageError("give --squeeze or --closing, not both");
    const sim::GraspClosing closing = parse_closing_option(args.text("closing"));
    if ((closing.jitter > 0) != args.has("jitter-from"))
      throw UsageError("a closing with jitter=X and --jitter-from RECORDING go together");
    setup.script = sim::make_grasp_script(
        setup.skeleton, setup.model, closing,
        args.has("jitter-from") ? recording_jitter(args.text("jitter-from")) : nullptr, posture);
  }
  std::function<void(const sim::HandSimState&)> observer;
  std::optional<FrameWriter> frames;
  if (args.has("frames")) {
    const double interval = args.number("frame-interval");
    if (!(interval > 0)) throw UsageError("--frame-interval must be positive");
    frames.emplace(setup, args.text("frames"), interval, args.number("view-yaw"),
                   args.flag("contacts"));
    observer = [&](const sim::HandSimState& s) { (*frames)(s); };
  }
  std::ostringstream trace;
  if (args.has("trace")) {
    trace << "time_s,cube_height_m,cube_turn_deg,grip_n,top_n,flesh_points_on_cube,bone_offset_mm,"
             "bone_turn_deg,farthest_bone\n";
    observer = [&, frame = observer](const sim::HandSimState& s) {
      if (frame) frame(s);
      write_trace_row(trace, setup, s);
    };
  }
  const sim::PinchReport r =
      sim::run_pinch(setup.model, setup.skeleton, setup.script, options, 0.0, observer);
  if (args.has("trace"))
    util::write_output(args.text("trace"), [&](std::ostream& out) { out << trace.str(); });
  // With --json - (or --trace -) standard output is that alone.
  if (args.text("json") != "-" && args.text("trace") != "-") print_pinch(setup, r);
  if (args.has("json"))
    util::write_output(args.text("json"),
                       [&](std::ostream& out) { write_pinch_json(out, setup, options, r); });
  return 0;
}

}  // namespace

int run_sim(const std::vector<std::string>& argv) {
  if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
    std::cout << family_usage({{sim_bench_help(), sim_bench_options()},
                               {sim_pinch_help(), sim_pinch_options()},
                               {sim_grasp_help(), sim_grasp_options()},
                               {sim_pinches_help(), sim_pinches_options()},
                               {sim_replay_help(), sim_replay_options()},
                               {sim_settle_help(), sim_settle_options()}});
    return 0;
  }
  if (argv.empty())
    throw UsageError("sim needs a command: bench, pinch, grasp, pinches, replay or settle");
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "bench") return sim_bench(rest);
  if (argv[0] == "pinch") return sim_pinch(rest);
  if (argv[0] == "grasp") return sim_grasp(rest);
  if (argv[0] == "pinches") return sim_pinches(rest);
  if (argv[0] == "replay") return sim_replay(rest);
  if (argv[0] == "settle") return sim_settle(rest);
  throw UsageError("unknown sim command '" + argv[0] +
                   "' (bench, pinch, grasp, pinches, replay, settle)");
}

}  // namespace handlab::cli
