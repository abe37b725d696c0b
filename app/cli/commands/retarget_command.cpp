// handlab-cli retarget: a recording through calibration and retargeting (Naive or Ours),
// with per-frame errors and a summary.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "analysis/stats/descriptives.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/commands/retarget_picture.h"
#include "core/hand/simulated_hand.h"
#include "core/retarget/retargeter.h"
#include "core/tracking/degraded_recording.h"
#include "core/tracking/recording_io.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

struct Stats {
  std::vector<double> values;
  double mean() const {
    double s = 0;
    for (double v : values) s += v;
    return values.empty() ? NAN : s / double(values.size());
  }
  double quantile(double p) const {  // NaN for none
    std::vector<double> v = values;
    std::sort(v.begin(), v.end());
    return stats::quantile_type7(v, p);
  }
};

}  // namespace

namespace {

std::vector<OptionSpec> retarget_options() {
  return {
      {"strategy", "naive|ours", "retargeting strategy", "ours"},
      {"hand", "right|left", "which tracked hand", "right"},
      {"sim-length", "METRES", "the simulated hand's length", "0.214"},
      {"csv", "FILE", "per-frame errors (deterministic: no timings)"},
      {"json", "OUT", "summary as JSON (- for standard output)"},
      {"picture", "FILE", "draw a pinch frame: tracked, Naive and Ours side by side (PNG)"},
      {"frame", "ID", "with --picture: this frame id instead of the strongest pinch"},
      {"timing-runs", "N",
       "time each frame in N runs of the recording and keep its fastest (what the frame "
       "costs, without other processes' interruptions)",
       "1"},
      {"joint-noise", "METRES",
       "degrade the recording as low tracking confidence does: noise of this standard "
       "deviation on every joint coordinate",
       "0"},
      {"jump-chance", "P",
       "degrade: each frame, each finger jumps (turns about its knuckle by up to 1 rad for 3 "
       "frames) with this chance",
       "0"},
      {"frame-rate", "HZ", "degrade: resample the recording to this frame rate (0: its own)", "0"},
      {"degrade-seed", "S", "the seed of the noise and the jumps", "1"},
  };
}

CommandHelp retarget_help() {
  return {"retarget",
          {"FILE [strategy] [hand] [sim-length] [csv] [json] [options]"},
          "Runs a recording through calibration (uniform scale from open-palm frames) and "
          "retargeting onto\n"
          "the simulated hand, and reports fingertip and pinch errors and timings."};
}

}  // namespace

namespace {

// --joint-noise, --jump-chance, --frame-rate and --degrade-seed, checked.
tracking::Degradation degradation_of(const Arguments& args) {
  tracking::Degradation degradation;
  degradation.joint_noise = args.number("joint-noise");
  degradation.jump_chance = args.number("jump-chance");
  degradation.rate_hz = args.number("frame-rate");
  const std::int64_t seed = args.integer("degrade-seed");
  if (!(degradation.joint_noise >= 0 && degradation.joint_noise <= 0.05))
    throw UsageError("--joint-noise must be 0 to 0.05 m");
  if (!(degradation.jump_chance >= 0 && degradation.jump_chance <= 1))
    throw UsageError("--jump-chance must be 0 to 1");
  if (!(degradation.rate_hz == 0 || (degradation.rate_hz >= 10 && degradation.rate_hz <= 1000)))
    throw UsageError("--frame-rate must be 0 or 10 to 1000 Hz");
  if (seed < 0) throw UsageError("--degrade-seed must be >= 0");
  degradation.seed = std::uint64_t(seed);
  return degradation;
}

bool degrades(const tracking::Degradation& d) {
  return d.joint_noise > 0 || d.jump_chance > 0 || d.rate_hz > 0;
}

// The recording's calibration: its open palm, or without one the ratio of hand lengths.
struct RecordingCalibration {
  retarget::Calibration calibration;
  std::string source;
};

RecordingCalibration calibrate(const tracking::Recording& recording, tracking::Side side,
                               const hand::Skeleton& simulated, double sim_length,
                               const tracking::TrackedHandFitter& fitter) {
  if (auto open = retarget::calibrate_open_palm(recording.frames, side, simulated, fitter))
    return {*open, "open palm"};
  retarget::Calibration c;
  c.scale = sim_length / *tracking::estimate_hand_length(recording.frames, side);
  return {c, "hand lengths"};
}

// Each frame's fastest time over `runs` - 1 runs, each from a fresh retargeter (the same warm
// starts frame by frame).
template <class MakeRetargeter>
std::vector<double> fastest_times_us(const std::vector<tracking::TrackedFrame>& played,
                                     tracking::Side side, std::int64_t runs,
                                     const MakeRetargeter& make_retargeter) {
  std::vector<double> fastest_us;
  for (std::int64_t run = 1; run < runs; ++run) {
    retarget::Retargeter timed = make_retargeter();
    std::size_t i = 0;
    for (const auto& frame : played) {
      const tracking::TrackedHand* h = frame.hand(side);
      if (!h) continue;
      const auto start = std::chrono::steady_clock::now();
      timed.retarget(*h);
      const double us =
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
              .count();
      if (i == fastest_us.size()) fastest_us.push_back(us);
      fastest_us[i] = std::min(fastest_us[i], us);
      ++i;
    }
  }
  return fastest_us;
}

const char* const kDigits[5] = {"thumb", "index", "middle", "ring", "pinky"};

// What the retargeting did, frame by frame and in summary.
struct RetargetMeasures {
  Stats time_us, iterations, pinch_gap;
  std::array<Stats, 5> tip_error, pinch_tip;
  double violation = 0.0;  // rad: the largest joint-limit violation
  int pinch_frames = 0;
  std::ostringstream csv;
};

// One frame's errors into `m` and its CSV row.
void measure_frame(const hand::Skeleton& simulated, const std::array<int, hand::kFingerCount>& tips,
                   const tracking::TrackedFrame& frame, const tracking::TrackedHand& h,
                   const retarget::RetargetResult& r, RetargetMeasures& m) {
  m.iterations.values.push_back(r.iterations);
  const hand::BoneFrames frames = hand::forward_kinematics(simulated, r.pose);
  std::array<Eigen::Vector3d, 5> got;
  m.csv << frame.id << ',' << frame.timestamp << ',' << h.pinch_strength << ',' << r.iterations;
  for (int f = 0; f < 5; ++f) {
    got[std::size_t(f)] = hand::marker_position(simulated, frames, tips[std::size_t(f)]);
    const double e = 1000 * (got[std::size_t(f)] - r.targets[std::size_t(f)]).norm();
    m.tip_error[std::size_t(f)].values.push_back(e);
    m.csv << ',' << e;
  }
  const double gap = 1000 * (got[0] - got[1]).norm(),
               target_gap = 1000 * (r.targets[0] - r.targets[1]).norm();
  double frame_violation = 0.0;
  for (std::size_t k = 0; k < simulated.dofs.size(); ++k) {
    const double a = r.pose.angles(Eigen::Index(k));
    frame_violation =
        std::max({frame_violation, simulated.dofs[k].lower - a, a - simulated.dofs[k].upper});
  }
  m.violation = std::max(m.violation, frame_violation);
  m.csv << ',' << gap << ',' << target_gap << ',' << frame_violation << '\n';
  if (h.pinch_strength >= 0.8) {
    ++m.pinch_frames;
    for (int f = 0; f < 2; ++f)
      m.pinch_tip[std::size_t(f)].values.push_back(m.tip_error[std::size_t(f)].values.back());
    m.pinch_gap.values.push_back(std::abs(gap - target_gap));
  }
}

// Every played frame of `side` retargeted and measured, its time the fastest of its runs.
void measure(const std::vector<tracking::TrackedFrame>& played, tracking::Side side,
             const hand::Skeleton& simulated, retarget::Retargeter& retargeter,
             const std::vector<double>& fastest_us, RetargetMeasures& m) {
  m.csv << std::setprecision(9) << "frame_id,timestamp_s,pinch_strength,iterations";
  for (const char* n : kDigits) m.csv << ',' << n << "_tip_error_mm";
  const auto tips = hand::fingertip_markers(simulated);
  m.csv << ",gap_intermediate_mm,gap_tracked_scaled_mm,joint_limit_violation_rad\n";
  for (const auto& frame : played) {
    const tracking::TrackedHand* h = frame.hand(side);
    if (!h) continue;
    const auto start = std::chrono::steady_clock::now();
    const retarget::RetargetResult r = retargeter.retarget(*h);
    double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    if (m.time_us.values.size() < fastest_us.size())
      us = std::min(us, fastest_us[m.time_us.values.size()]);
    m.time_us.values.push_back(us);
    measure_frame(simulated, tips, frame, *h, r, m);
  }
}

// What the command was asked, for its printout and JSON.
struct RetargetRun {
  std::string source, strategy, hand;
  RecordingCalibration calibration;
  std::optional<tracking::Degradation> degradation;
  std::int64_t timing_runs = 1;
};

void print_summary(const RetargetRun& run, const RetargetMeasures& m) {
  std::cout << std::fixed << std::setprecision(2) << run.source << ": " << run.strategy << ", "
            << m.time_us.values.size() << " frames, scale " << run.calibration.calibration.scale
            << " (" << run.calibration.source << ")";
  if (const auto& d = run.degradation)
    std::cout << ", degraded: joint noise " << 1000 * d->joint_noise << " mm, jumps "
              << 100 * d->jump_chance << " % a finger and frame, "
              << (d->rate_hz > 0 ? std::to_string(int(d->rate_hz)) + " Hz"
                                 : std::string("its own frame rate"))
              << ", seed " << d->seed;
  std::cout << "\n  time per frame: median " << m.time_us.quantile(0.5) << " us, p99 "
            << m.time_us.quantile(0.99) << " us; iterations mean " << m.iterations.mean()
            << ", max " << m.iterations.quantile(1.0) << "\n  fingertip error (mm, mean / p95):";
  for (int f = 0; f < 5; ++f)
    std::cout << " " << kDigits[f] << " " << m.tip_error[std::size_t(f)].mean() << " / "
              << m.tip_error[std::size_t(f)].quantile(0.95);
  std::cout << "\n  pinch frames " << m.pinch_frames << ": thumb " << m.pinch_tip[0].mean()
            << ", index " << m.pinch_tip[1].mean() << " mm; gap error mean " << m.pinch_gap.mean()
            << " mm, p95 " << m.pinch_gap.quantile(0.95) << " mm\n  joint limit violation max "
            << m.violation << " rad\n";
}

void write_summary_json(std::ostream& out, const RetargetRun& run, const RetargetMeasures& m) {
  auto mean_p95 = [](util::JsonWriter& json, const Stats& s) {
    json.begin_object().field("mean", s.mean()).field("p95", s.quantile(0.95)).end_object();
  };
  util::JsonWriter json(out);
  json.begin_object()
      .field("source", run.source)
      .field("strategy", run.strategy)
      .field("hand", run.hand);
  json.field("scale", run.calibration.calibration.scale)
      .field("calibration", run.calibration.source);
  if (const auto& d = run.degradation)
    json.key("degradation")
        .begin_object()
        .field("joint_noise_m", d->joint_noise)
        .field("jump_chance", d->jump_chance)
        .field("frame_rate_hz", d->rate_hz)
        .field("seed", double(d->seed))
        .end_object();
  json.field("frames", m.time_us.values.size());
  json.key("time_us")
      .begin_object()
      .field("median", m.time_us.quantile(0.5))
      .field("p99", m.time_us.quantile(0.99))
      .field("runs", int(run.timing_runs))
      .end_object();
  json.key("iterations")
      .begin_object()
      .field("mean", m.iterations.mean())
      .field("max", m.iterations.quantile(1.0))
      .end_object();
  json.key("tip_error_mm").begin_object();
  for (int f = 0; f < 5; ++f) {
    json.key(kDigits[f]);
    mean_p95(json, m.tip_error[std::size_t(f)]);
  }
  json.end_object();
  json.field("pinch_frames", m.pinch_frames);
  json.key("pinch_tip_error_mm").begin_object();
  json.key("thumb");
  mean_p95(json, m.pinch_tip[0]);
  json.key("index");
  mean_p95(json, m.pinch_tip[1]);
  json.end_object();
  json.key("pinch_gap_error_mm");
  mean_p95(json, m.pinch_gap);
  json.field("joint_limit_violation_max_rad", m.violation);
  json.end_object();
}

// --picture (and --frame): a pinch frame tracked, by Naive and by Ours.
void draw_picture(const Arguments& args, const tracking::Recording& recording, tracking::Side side,
                  const hand::HandShape& shape, const retarget::Calibration& calibration,
                  const tracking::TrackedHandFitter& fitter) {
  std::optional<std::int64_t> frame_id;
  if (args.has("frame")) frame_id = args.integer("frame");
  const std::int64_t id = write_retarget_picture(recording, side, shape, calibration, fitter,
                                                 frame_id, args.text("picture"));
  std::cout << "wrote " << args.text("picture") << " (frame " << id << ")\n";
}

}  // namespace

int run_retarget(const std::vector<std::string>& argv) {
  const Arguments args(retarget_options(), argv, 1);
  if (args.help_requested()) return print_help(retarget_help(), args);
  if (args.positional().empty()) throw UsageError("name a recording");
  RetargetRun run;
  run.strategy = args.choice("strategy", {"naive", "ours"});
  run.hand = args.choice("hand", {"right", "left"});
  const double sim_length = args.number("sim-length");
  if (sim_length < 0.1 || sim_length > 0.3)
    throw UsageError("--sim-length must be between 0.1 and 0.3 m");
  const auto strategy =
      run.strategy == "naive" ? retarget::Strategy::kNaive : retarget::Strategy::kOurs;
  const auto side = run.hand == "left" ? tracking::Side::kLeft : tracking::Side::kRight;
  run.timing_runs = args.integer("timing-runs");
  if (run.timing_runs < 1 || run.timing_runs > 1000)
    throw UsageError("--timing-runs must be 1 to 1000");
  const tracking::Degradation degradation = degradation_of(args);
  if (degrades(degradation)) run.degradation = degradation;

  const tracking::Recording recording = tracking::read_recording(args.positional()[0]);
  run.source = recording.source;
  hand::HandShape shape = hand::HandShape::with_length(sim_length);
  shape.left = side == tracking::Side::kLeft;
  const hand::Skeleton simulated = hand::build_simulated_hand(shape);
  auto fitter = tracking::TrackedHandFitter::for_recording(recording.frames, side);
  if (!fitter)
    throw std::runtime_error(recording.source + ": no " + run.hand + " hand in the recording");
  run.calibration = calibrate(recording, side, simulated, sim_length, *fitter);
  // Calibrated on the recording as recorded (a held open hand); retargeted on its frames
  // degraded when asked.
  std::vector<tracking::TrackedFrame> degraded;
  if (run.degradation) degraded = tracking::degrade(recording.frames, degradation);
  const std::vector<tracking::TrackedFrame>& played = run.degradation ? degraded : recording.frames;
  if (args.has("picture"))
    draw_picture(args, recording, side, shape, run.calibration.calibration, *fitter);
  auto make_retargeter = [&] {
    return retarget::Retargeter(strategy, simulated, run.calibration.calibration,
                                strategy == retarget::Strategy::kNaive ? fitter : std::nullopt);
  };
  const std::vector<double> fastest_us =
      fastest_times_us(played, side, run.timing_runs, make_retargeter);
  retarget::Retargeter retargeter = make_retargeter();
  RetargetMeasures measures;
  measure(played, side, simulated, retargeter, fastest_us, measures);
  if (args.has("csv"))
    util::write_output(args.text("csv"), [&](std::ostream& out) { out << measures.csv.str(); });
  const std::string json_out = args.text("json");
  if (json_out != "-") print_summary(run, measures);
  if (!json_out.empty())
    util::write_output(json_out,
                       [&](std::ostream& out) { write_summary_json(out, run, measures); });
  return 0;
}

}  // namespace handlab::cli
