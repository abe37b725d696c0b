// handlab-cli sim replay: a real recording, calibrated and retargeted onto the study hand, drives
// the soft hand in free motion (the cube out of reach): the simulator's cost on tracked input,
// which moves as a person's hand does (fast, with tremor and the tracker's jitter), where `sim
// bench` measures a smooth scripted pinch. With --hold the hand is held still in one of the
// recording's poses: it should come to rest.
#include "app/cli/commands/sim_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "analysis/stats/descriptives.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/sim_grasp.h"
#include "app/cli/commands/step_parts.h"
#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/retarget/recording_poses.h"
#include "core/sim/hand_simulator.h"
#include "core/sim/step_totals.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

using stats::timing_quantile;

// What replaying the poses on the soft hand cost and left.
struct ReplayFigures {
  int steps = 0;
  std::vector<double> step_ms;
  sim::StepTotals totals;       // their factorisations, CG iterations and time by part
  double fastest_at_end = 0.0;  // m/s: the fastest flesh node in the last 0.5 s
};

// The recording's poses (or its pose `held`, held: -1 plays them) played on the soft hand for
// `duration` s, the cube out of reach, each step taking the latest pose.
ReplayFigures replay_poses(const retarget::RecordingPoses& replay, const sim::HandSimModel& model,
                           int held, double duration, const sim::SimOptions& options) {
  const hand::Skeleton& skeleton = replay.skeleton;
  const std::vector<hand::HandPose>& poses = replay.poses;
  const std::vector<double>& times = replay.times;
  const bool hold = held >= 0;
  sim::HandSimulator simulator(model, options);
  std::size_t frame = hold ? std::size_t(held) : 0;
  Eigen::Isometry3d root = Eigen::Isometry3d::Identity();
  root.linear() = poses[frame].root_rotation;
  root.translation() = poses[frame].root_position;
  sim::RigidPose cube;  // out of reach
  cube.position = root.translation() + Eigen::Vector3d(1.0, 0, 0);
  cube.position.y() = model.parameters.cube_size / 2;
  sim::HandSimState state = sim::initial_state(model, skeleton, root, cube);
  const double h = model.parameters.time_step;
  ReplayFigures f;
  f.steps = int(std::floor(duration / h));
  for (int i = 0; i < f.steps; ++i) {
    const double t = times.front() + double(i) * h;
    while (!hold && frame + 1 < times.size() && times[frame + 1] <= t) ++frame;
    const std::vector<sim::RigidPose> targets = sim::bone_targets(model, skeleton, poses[frame]);
    const auto start = std::chrono::steady_clock::now();
    const sim::SimStepReport r = simulator.step(state, targets);
    f.step_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    f.totals.add(r, 1e-3 * f.step_ms.back());
    if (double(f.steps - i) * h <= 0.5)
      for (const Eigen::Vector3d& v : state.node_velocity)
        f.fastest_at_end = std::max(f.fastest_at_end, v.norm());
  }
  return f;
}

}  // namespace

std::vector<OptionSpec> sim_replay_options() {
  return {
      {"strategy", "naive|ours", "the retargeting", "ours"},
      {"hold", "", "hold one of the recording's poses still instead of playing it"},
      {"frame", "K", "with --hold: the pose held, the K-th of the recording's hand frames", "0"},
      {"duration", "SECONDS", "with --hold: how long (default: the recording's length)"},
      {"threads", "N", "threads the flesh's work is split over", "1"},
      {"newton-iterations", "N", "Newton iterations a step", "1"},
      {"stiffening-blend", "FRACTION",
       "of the stiffening threshold, below it, over which Newton's matrix takes in the "
       "stiffening (0: a matrix that jumps at the threshold)",
       "0.2"},
      physics_option(),
      {"json", "OUT", "write the result as JSON (- for standard output)"},
  };
}

CommandHelp sim_replay_help() {
  return {"sim replay",
          {"RECORDING [strategy] [hold] [json] [options]"},
          "Plays a recording (its right hand, or its left), calibrated and retargeted onto the "
          "21.4 cm study\n"
          "hand, on the soft hand in free motion, one step of 1/120 s taking the latest frame; "
          "reports the\n"
          "step times, factorisations and CG iterations, and how fast the flesh still moves at "
          "the end."};
}

int sim_replay(const std::vector<std::string>& argv) {
  const Arguments args(sim_replay_options(), argv, 1);
  if (args.help_requested()) return print_help(sim_replay_help(), args);
  if (args.positional().size() != 1) throw UsageError("name one recording");
  const std::string strategy_name = args.choice("strategy", {"naive", "ours"});
  const long threads_asked = args.integer("threads");
  if (threads_asked < 1 || threads_asked > 64) throw UsageError("--threads must be 1 to 64");
  const int threads = int(threads_asked);

  const tracking::Recording recording = tracking::read_recording(args.positional()[0]);
  const retarget::RecordingPoses replay = retarget::retarget_recording(
      recording, strategy_name == "naive" ? retarget::Strategy::kNaive : retarget::Strategy::kOurs);
  const bool hold = args.flag("hold");  // the poses are of the study's hand, 21.4 cm
  const double length = replay.times.back() - replay.times.front();
  const double duration = hold && args.has("duration") ? args.number("duration") : length;
  if (!(duration > 0 && duration <= 600)) throw UsageError("--duration must be in (0, 600] s");
  if (args.has("frame") && !hold) throw UsageError("--frame needs --hold");
  const long frame = args.integer("frame");
  if (frame < 0 || frame >= long(replay.poses.size()))
    throw UsageError("--frame must be 0 to " + std::to_string(replay.poses.size() - 1));
  const long newton_iterations = args.integer("newton-iterations");
  if (newton_iterations < 1 || newton_iterations > 20)
    throw UsageError("--newton-iterations must be 1 to 20");
  sim::SimOptions options;
  options.threads = threads;
  options.newton_iterations = int(newton_iterations);

  const hand::HandFlesh flesh = hand::build_flesh(replay.skeleton, replay.shape);
  sim::SimParameters parameters;
  parameters.stiffening_blend = args.number("stiffening-blend");
  if (!(parameters.stiffening_blend >= 0 && parameters.stiffening_blend < 1))
    throw UsageError("--stiffening-blend must be in [0, 1)");
  apply_physics_option(args, parameters);
  const sim::HandSimModel model = sim::make_hand_sim_model(replay.skeleton, flesh, parameters);
  const ReplayFigures f = replay_poses(replay, model, hold ? int(frame) : -1, duration, options);
  const double median = timing_quantile(f.step_ms, 0.5), p95 = timing_quantile(f.step_ms, 0.95);
  const std::string json_out = args.text("json");
  if (json_out != "-") {
    std::string changed;
    for (const std::string& item : args.all("physics")) changed += ", " + item;
    std::cout << std::fixed << std::setprecision(2) << recording.source << " (" << strategy_name
              << (hold ? ", pose " + std::to_string(frame) + " held still" : "") << changed
              << "): " << f.steps << " steps, median " << median << " ms, p95 " << p95 << " ms; "
              << f.totals.factorizations << " factorisations, CG "
              << double(f.totals.linear_iterations) / f.steps
              << " a step; fastest flesh node in the last 0.5 s " << std::setprecision(3)
              << f.fastest_at_end * 1000 << " mm/s\n"
              << std::setprecision(2);
    print_step_parts(std::cout, f.totals);
  }
  if (args.has("json")) {
    util::write_output(json_out, [&](std::ostream& out) {
      util::JsonWriter json(out);
      json.begin_object()
          .field("recording", recording.source)
          .field("strategy", strategy_name)
          .field("hold", hold)
          .field("frame", static_cast<long long>(hold ? frame : -1))
          .field("threads", threads)
          .field("newton_iterations", options.newton_iterations)
          .field("stiffening_blend", model.parameters.stiffening_blend);
      write_physics(json, args.all("physics"));
      json.field("steps", f.steps)
          .field("step_ms_median", median)
          .field("step_ms_p95", p95)
          .field("factorizations", static_cast<long long>(f.totals.factorizations))
          .field("linear_iterations_per_step", double(f.totals.linear_iterations) / f.steps)
          .field("fastest_node_last_half_second_m_s", f.fastest_at_end);
      write_step_parts(json, f.totals);
      json.end_object();
    });
  }
  return 0;
}

}  // namespace handlab::cli
