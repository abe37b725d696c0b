// handlab-cli sim grasp: the pinch-lift-hold-release of each cube over a grid of closings,
// each factor alone from the scripted pinch: which closings the soft hand's grip holds.
#include "app/cli/commands/sim_grasp.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "analysis/stats/proportion_difference.h"
#include "analysis/stats/wilson_interval.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/grasp_map_file.h"
#include "app/cli/progress_line.h"
#include "core/hand/hand_shape.h"
#include "core/retarget/recording_poses.h"
#include "core/sim/sim_parameter_names.h"
#include "core/task/finger_pads.h"
#include "core/task/grasp_comparison.h"
#include "core/task/grasp_map.h"
#include "core/task/grasp_repeats.h"
#include "core/task/human_closings.h"
#include "core/task/pad_jitter.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {
namespace {

struct CubeMap {
  double cube_size = 0.0;
  int repeats = 1;  // runs of each closing (--repeats)
  std::vector<sim::GraspOutcome> outcomes;
  std::optional<sim::GraspComparison> against;  // with --against, when its map has this cube
  bool against_missing = false;                 // with --against, when it has not
  // With --jitter-from: the recording's jitter at the scripted pinch's pads, at each of the
  // jitter factor's levels but 0.
  std::vector<sim::PadJitter> pad_jitter;
};

// "over_closure 10 mm" for a factor's level, the closing's description for a pair or a draw.
// A repeat's (sim grasp --repeats) label ends in its number (1, 2, ...; 0 is the closing as
// given).
std::string closing_label(const sim::ClosingPoint& p) {
  const std::string repeat = p.repeat > 0 ? " (repeat " + std::to_string(p.repeat) + ")" : "";
  if (p.factor.empty()) return "the scripted pinch" + repeat;
  if (p.factor == "pair" || p.factor == "draw" || p.factor == "closing")
    return (p.factor == "draw" ? "draw " + std::to_string(int(p.level)) + ": " : "") +
           sim::describe(p.closing) + repeat;
  return sim::describe_level(sim::closing_factor(p.factor), p.level) + repeat;
}

// The draws' hold rate over their runs; its interval counts each draw once (its repeats are
// not independent of each other): the Wilson interval of the rate over the draws.
struct DrawRate {
  int closings = 0, runs = 0, held = 0;
  double rate = 0.0;
  stats::ProportionInterval interval;
};
DrawRate draw_rate(const std::vector<sim::GraspOutcome>& outcomes) {
  DrawRate d;
  for (const sim::GraspOutcome& o : outcomes) {
    if (o.point.factor != "draw") continue;
    d.closings += o.point.repeat == 0 ? 1 : 0;
    ++d.runs;
    d.held += o.measures.held ? 1 : 0;
  }
  if (d.runs > 0) {
    d.rate = double(d.held) / d.runs;
    d.interval = stats::wilson_interval(double(d.held) * d.closings / d.runs, d.closings);
  }
  return d;
}

std::string group_of(const sim::ClosingPoint& p) {
  return p.factor.empty() ? "scripted" : p.factor == "pair" ? "pairs" : p.factor;
}

// The grid's closings within half of every factor's range (grasp_closing.h), which the grip
// must hold whole, and those of them it lost; the draws are not a grid's.
void print_within_half(const CubeMap& map) {
  int run = 0, held = 0;
  std::string lost;
  for (const sim::GraspOutcome& o : map.outcomes) {
    if (!sim::in_half_of_grid(o.point)) continue;
    ++run;
    held += o.measures.held ? 1 : 0;
    if (!o.measures.held) lost += "\n  - " + closing_label(o.point);
  }
  if (run > 0)
    std::printf("within half of every range: %d of %d held%s\n", held, run,
                lost.empty() ? "" : (", lost:" + lost).c_str());
}

// The lost runs by how they lost the cube (pinch_loss.h).
void print_losses(const CubeMap& map) {
  std::map<sim::PinchLoss, int> count;
  for (const sim::GraspOutcome& o : map.outcomes)
    if (!o.measures.held) ++count[o.loss];
  if (count.empty()) return;
  std::printf("lost:");
  for (const auto& [loss, n] : count) std::printf(" %s %d;", sim::pinch_loss_name(loss), n);
  std::printf("\n");
}

// With --repeats: how many closings were held every time, never, and only sometimes.
void print_repeats(const CubeMap& map) {
  const std::vector<sim::RepeatedClosing> closings = sim::group_by_closing(map.outcomes);
  if (closings.size() == map.outcomes.size()) return;
  for (bool within_half : {false, true}) {
    const sim::RepeatCounts c = sim::count_repeats(closings, within_half);
    if (c.closings > 0)
      std::printf("%s, %d closing%s: held in every repeat %d, in none %d, in some %d\n",
                  within_half ? "within half of every range" : "repeated", c.closings,
                  c.closings == 1 ? "" : "s", c.every, c.none, c.some);
  }
}

void print_closings(const char* title, const std::vector<sim::ClosingPoint>& points) {
  std::printf("%s: %zu\n", title, points.size());
  for (const sim::ClosingPoint& p : points) std::printf("  - %s\n", closing_label(p).c_str());
}

// A closing's hold rate now against before, over the repeats of each: a change the repeats
// resolve when Newcombe's interval of the difference (now - before) excludes zero; a closing
// held in five repeats before and four now is not one.
struct RateChange {
  stats::ProportionDifference difference;
  int direction = 0;  // -1 held less often now, +1 more often, 0 not resolved
};
RateChange rate_change(const sim::ClosingHoldCounts& c) {
  RateChange r{
      stats::newcombe_difference(c.held_after, c.runs_after, c.held_before, c.runs_before)};
  r.direction = r.difference.high < 0 ? -1 : r.difference.low > 0 ? 1 : 0;
  return r;
}

void print_rate_changes(const std::vector<sim::ClosingHoldCounts>& counts) {
  std::vector<const sim::ClosingHoldCounts*> less, more;
  for (const sim::ClosingHoldCounts& c : counts) {
    const int direction = rate_change(c).direction;
    if (direction < 0) less.push_back(&c);
    if (direction > 0) more.push_back(&c);
  }
  std::printf(
      "by closing over its repeats: %zu closings; held less often now by more than the repeats "
      "resolve (Newcombe's 95 %% interval of the difference below 0): %zu; more often: %zu\n",
      counts.size(), less.size(), more.size());
  for (const auto& [title, list] : {std::pair{"less often", &less}, std::pair{"more often", &more}})
    for (const sim::ClosingHoldCounts* c : *list) {
      const stats::ProportionDifference d = rate_change(*c).difference;
      std::printf("  - %s: held %d of %d before, %d of %d now (%+.2f, %+.2f to %+.2f): %s\n", title,
                  c->held_before, c->runs_before, c->held_after, c->runs_after, d.difference, d.low,
                  d.high, closing_label(c->point).c_str());
    }
}

void print_comparison(const sim::GraspComparison& c) {
  std::printf(
      "against the map before: %d closings in both, held %d before and %d now (held and "
      "released %d and %d)",
      c.in_both, c.held_before, c.held_after, c.released_before, c.released_after);
  if (c.only_after > 0) std::printf(" (%d not in it)", c.only_after);
  std::printf("\n");
  print_closings("held before, lost now", c.held_before_lost_after);
  print_closings("lost before, held now", c.lost_before_held_after);
  if (!c.repeated.empty()) print_rate_changes(c.repeated);
}

void print_pad_jitter(const CubeMap& map) {
  if (map.pad_jitter.empty()) return;
  std::printf(
      "the jitter at the scripted pinch's pads (thumb, index; the index's against the "
      "thumb's along and across the pinch; its speed, RMS and largest):\n");
  for (const sim::PadJitter& p : map.pad_jitter)
    std::printf("  %g x: %.2f, %.2f mm; %.2f, %.2f mm; %.1f, %.1f cm/s\n", p.scale,
                1000 * p.thumb_rms, 1000 * p.index_rms, 1000 * p.along_rms, 1000 * p.across_rms,
                100 * p.relative_speed_rms, 100 * p.relative_speed_max);
}

void print_map(const CubeMap& map) {
  // "top N": the flesh's load on the cube's top before the closing (PinchReport).
  std::printf("\ncube %.0f mm\n%-4s %-8s %8s %10s %7s %6s %6s  %s\n", map.cube_size * 1000, "held",
              "released", "slip mm", "deepest mm", "grip N", "turn", "top N", "closing");
  std::vector<std::pair<std::string, std::pair<int, int>>> held;  // group -> held, run
  for (const sim::GraspOutcome& o : map.outcomes) {
    const sim::PinchReport& m = o.measures;
    // A posture the pinch's rule could not clear (pinch_clearance.h) is marked.
    char unmet[96] = "";
    if (o.placed_by_rule && !o.meets_pinch_rule)
      std::snprintf(unmet, sizeof unmet,
                    " (the pinch's rule not met: pads %.1f mm off, other skin %.1f mm off)",
                    o.placement_pad_error_mm, o.pinch_clearance_mm);
    std::printf("%-4s %-8s %8.3f %10.2f %7.2f %5.1f° %6.1f  %s%s\n", m.held ? "yes" : "NO",
                m.released ? "yes" : "NO", m.slip_mm, m.max_penetration_mm, m.peak_grip_n,
                m.turn_deg, m.top_load_before_closing_n, closing_label(o.point).c_str(), unmet);
    const std::string group = group_of(o.point);
    if (held.empty() || held.back().first != group) held.push_back({group, {0, 0}});
    held.back().second.first += m.held ? 1 : 0;
    ++held.back().second.second;
  }
  print_pad_jitter(map);
  print_within_half(map);
  if (map.against) print_comparison(*map.against);
  if (map.against_missing)
    std::printf("the map before has no %.0f mm cube\n", map.cube_size * 1000);
  std::printf("held:");
  for (const auto& [group, count] : held) {
    std::printf(" %s %d of %d", group.c_str(), count.first, count.second);
    if (group == "draw") {
      const DrawRate d = draw_rate(map.outcomes);
      std::printf(" (%.0f %%, 95 %% CI %.0f-%.0f %%)", 100.0 * d.rate, 100 * d.interval.low,
                  100 * d.interval.high);
    }
    std::printf(";");
  }
  std::printf("\n");
  print_losses(map);
  print_repeats(map);
}

void write_closing(util::JsonWriter& json, const sim::GraspOutcome& o) {
  json.begin_object()
      .field("factor", o.point.factor)
      .field("level", o.point.level)
      .field("closing", sim::describe(o.point.closing))
      .field("repeat", o.point.repeat)
      .key("cube_shift_mm")
      .begin_array()
      .value(1000 * o.point.closing.cube_shift_x)
      .value(1000 * o.point.closing.cube_shift_z)
      .end_array()
      .key("values")
      .begin_object();
  for (const sim::ClosingFactor& f : sim::closing_factors())
    json.field(f.name, o.point.closing.*(f.field) / f.scale);
  json.end_object();
  write_pinch_measures(json, o.measures);
  json.field("within_half", sim::within_half_of_ranges(o.point.closing))
      .field("pinch_error_mm", o.pinch_error_mm)
      .field("pinch_clearance_mm", o.pinch_clearance_mm)
      .field("placement_pad_error_mm", o.placement_pad_error_mm)
      .field("open_clearance_mm", o.open_clearance_mm)
      .field("placed_by_rule", o.placed_by_rule)
      .field("meets_pinch_rule", o.meets_pinch_rule)
      .field("loss", sim::pinch_loss_name(o.loss))
      .field("pushed_mm", o.pushed_mm)
      .field("grip_at_lift_n", o.grip_at_lift_n)
      // null where a pad never touched the cube (NaN is written as null)
      .field("touch_lead_ms", o.touch_lead_ms.value_or(std::nan("")))
      .field("turn_at_touch_deg", o.turn_at_touch_deg.value_or(std::nan("")))
      .end_object();
}

// What a map was run with, besides its closings.
struct MapRun {
  int draws = 0;
  std::uint64_t seed = 0;
  std::vector<std::string> physics;  // --physics NAME=VALUE
  std::string jitter_from;
  std::shared_ptr<const sim::PoseJitter> jitter;
  sim::PinchPosture posture = sim::PinchPosture::kSolved;
};

// The factors, their levels and the human distribution's parameters with their sources.
void write_factors(util::JsonWriter& json, const MapRun& run) {
  json.key("factors").begin_array();
  for (const sim::ClosingFactor& f : sim::closing_factors()) {
    json.begin_object().field("name", f.name).field("unit", f.unit).key("levels").begin_array();
    for (double level : f.levels) json.value(level);
    json.end_array().key("pair_levels").begin_array();
    for (double level : f.pair_levels) json.value(level);
    json.end_array().end_object();
  }
  json.end_array()
      .key("human_distribution")
      .begin_object()
      .field("draws", run.draws)
      .field("seed", run.seed);
  json.key("parameters").begin_array();
  for (const sim::ClosingParameter& p : sim::human_closing_parameters())
    json.begin_object()
        .field("factor", p.factor)
        .field("distribution", p.distribution)
        .field("source", p.source)
        .field("assumption", p.assumption)
        .end_object();
  json.end_array().end_object();
}

void write_points(util::JsonWriter& json, const char* key,
                  const std::vector<sim::ClosingPoint>& points) {
  json.key(key).begin_array();
  for (const sim::ClosingPoint& p : points) json.value(closing_label(p));
  json.end_array();
}

void write_comparison(util::JsonWriter& json, const sim::GraspComparison& c) {
  json.key("against")
      .begin_object()
      .field("in_both", c.in_both)
      .field("held_before", c.held_before)
      .field("held_after", c.held_after)
      .field("held_and_released_before", c.released_before)
      .field("held_and_released_after", c.released_after)
      .field("not_in_before", c.only_after);
  write_points(json, "held_before_lost_after", c.held_before_lost_after);
  write_points(json, "lost_before_held_after", c.lost_before_held_after);
  if (!c.repeated.empty()) {
    int less = 0, more = 0;
    json.key("by_closing").begin_array();
    for (const sim::ClosingHoldCounts& r : c.repeated) {
      const RateChange change = rate_change(r);
      const stats::ProportionDifference& d = change.difference;
      less += change.direction < 0 ? 1 : 0;
      more += change.direction > 0 ? 1 : 0;
      json.begin_object()
          .field("closing", closing_label(r.point))
          .field("runs_before", r.runs_before)
          .field("held_before", r.held_before)
          .field("runs_after", r.runs_after)
          .field("held_after", r.held_after)
          .field("difference", d.difference)
          .field("difference_low", d.low)
          .field("difference_high", d.high)
          .end_object();
    }
    json.end_array().field("held_less_often", less).field("held_more_often", more);
  }
  json.end_object();
}

// What the jitter factor's levels do at the scripted pinch's pads (null without a recording).
void write_pad_jitter(util::JsonWriter& json, const std::vector<sim::PadJitter>& levels) {
  json.key("pad_jitter");
  if (levels.empty()) {
    json.null();
    return;
  }
  json.begin_array();
  for (const sim::PadJitter& p : levels)
    json.begin_object()
        .field("jitter", p.scale)
        .field("thumb_rms_mm", 1000 * p.thumb_rms)
        .field("index_rms_mm", 1000 * p.index_rms)
        .field("along_rms_mm", 1000 * p.along_rms)
        .field("across_rms_mm", 1000 * p.across_rms)
        .field("relative_speed_rms_cm_s", 100 * p.relative_speed_rms)
        .field("relative_speed_max_cm_s", 100 * p.relative_speed_max)
        .end_object();
  json.end_array();
}

// A cube's closings, how many held, and the draws' hold rate with its Wilson interval.
void write_cube_map(util::JsonWriter& json, const CubeMap& map) {
  json.begin_object().field("cube_size_m", map.cube_size).key("closings").begin_array();
  int held = 0;
  for (const sim::GraspOutcome& o : map.outcomes) {
    write_closing(json, o);
    held += o.measures.held ? 1 : 0;
  }
  json.end_array().field("held", held).field("closings_run", int(map.outcomes.size()));
  write_pad_jitter(json, map.pad_jitter);
  if (map.against) write_comparison(json, *map.against);
  const DrawRate d = draw_rate(map.outcomes);
  if (d.runs > 0)
    json.key("draws")
        .begin_object()
        .field("run", d.runs)
        .field("held", d.held)
        .field("hold_rate", d.rate)
        .field("hold_rate_low", d.interval.low)
        .field("hold_rate_high", d.interval.high)
        .end_object();
  const std::vector<sim::RepeatedClosing> closings = sim::group_by_closing(map.outcomes);
  json.key("repeats").begin_object().field("per_closing", map.repeats);
  for (bool within_half : {false, true}) {
    const sim::RepeatCounts c = sim::count_repeats(closings, within_half);
    json.key(within_half ? "within_half" : "all")
        .begin_object()
        .field("closings", c.closings)
        .field("held_every_time", c.every)
        .field("held_never", c.none)
        .field("held_sometimes", c.some)
        .end_object();
  }
  json.end_object().end_object();
}

void write_posture(util::JsonWriter& json, sim::PinchPosture posture) {
  json.field("posture", sim::pinch_posture_name(posture));
  if (posture != sim::PinchPosture::kFunctional) return;
  const sim::FunctionalPosture& p = sim::functional_posture();
  json.key("functional_posture").begin_object().field("weight_m_per_rad", p.weight);
  json.key("angles").begin_array();
  for (const sim::PostureAngle& a : p.angles)
    json.begin_object()
        .field("dof", a.dof)
        .field("angle_deg", a.angle * 180 / M_PI)
        .field("source", a.source)
        .end_object();
  json.end_array().end_object();
}

void write_map_json(const std::vector<CubeMap>& maps, const MapRun& run, std::ostream& out) {
  util::JsonWriter json(out);
  json.begin_object();
  write_physics(json, run.physics);
  write_posture(json, run.posture);
  json.key("jitter");
  if (run.jitter)
    json.begin_object()
        .field("recording", run.jitter_from)
        .field("root_rms_mm", 1000 * run.jitter->root_rms())
        .field("angle_rms_deg", run.jitter->angle_rms() * 180 / M_PI)
        .end_object();
  else
    json.null();
  write_factors(json, run);
  json.key("cubes").begin_array();
  for (const CubeMap& map : maps) write_cube_map(json, map);
  json.end_array().end_object();
  out << "\n";
}

// The grid's closings: the --closing ones, each --factor (or every one) alone, or the pairs.
std::vector<sim::ClosingPoint> grid_of(const Arguments& args, const std::string& grid, long draws,
                                       bool with_jitter) {
  if (args.has("closing")) {
    if (args.has("factor") || args.has("grid") || draws > 0)
      throw UsageError("give --closing alone, not with --factor, --grid or --draws");
    std::vector<sim::ClosingPoint> points;
    for (const std::string& text : args.all("closing"))
      points.push_back({"closing", 0.0, parse_closing_option(text)});
    return points;
  }
  if (grid == "single") {
    try {
      for (const std::string& f : args.all("factor")) sim::closing_factor(f);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--factor: ") + e.what());
    }
    return sim::single_factor_grid(args.all("factor"), with_jitter);
  }
  if (args.has("factor"))
    throw UsageError("--factor maps single factors: give it with --grid single");
  return grid == "pairs" ? sim::factor_pairs_grid(with_jitter) : std::vector<sim::ClosingPoint>{};
}

// `map` beside the same cube's map in `before`, if it has one.
std::optional<sim::GraspComparison> compare_with(const std::vector<MappedCube>& before,
                                                 const CubeMap& map) {
  for (const MappedCube& cube : before) {
    if (std::abs(cube.cube_size - map.cube_size) > 1e-9) continue;
    std::vector<sim::MappedClosing> after;
    for (const sim::GraspOutcome& o : map.outcomes)
      after.push_back({o.point, o.measures.held, o.measures.released});
    return sim::compare_maps(cube.closings, after);
  }
  return std::nullopt;
}

// The jitter factor's levels but 0 at the scripted pinch's pads, sampled at the simulator's step.
std::vector<sim::PadJitter> jitter_at_pads(const sim::PinchScene& scene,
                                           const sim::PoseJitter& jitter) {
  const sim::PinchPads pads = sim::pinch_pads(scene.skeleton, scene.model);
  std::vector<sim::PadJitter> levels;
  for (double level : sim::closing_factor("jitter").levels)
    if (level > 0)
      levels.push_back(sim::pad_jitter(scene.skeleton, scene.script.pinch, pads, jitter, level,
                                       scene.model.parameters.time_step));
  return levels;
}

// One cube's closings run side by side, with progress lines: the placements', the runs'.
CubeMap map_cube(const sim::PinchScene& scene, double side,
                 const std::vector<sim::ClosingPoint>& points, int jobs, bool quiet,
                 std::chrono::steady_clock::time_point start) {
  ProgressLine placing(quiet), progress(quiet);
  CubeMap map;
  map.cube_size = side;
  const auto show = [&](ProgressLine& line, const char* what, int done, std::size_t count) {
    char text[120];
    std::snprintf(text, sizeof text, "cube %.0f mm: %s %d/%zu  %.0f s", map.cube_size * 1000, what,
                  done, count,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    line.show(done, text);
  };
  map.outcomes = sim::run_grasp_map(
      scene, points, jobs, [&](int done) { show(progress, "closings", done, points.size()); },
      [&](int placed, int to_place) {
        show(placing, "placements", placed, std::size_t(to_place));
        if (placed == to_place) placing.finish();
      });
  progress.finish();
  return map;
}

}  // namespace

sim::GraspClosing parse_closing_option(const std::string& text) {
  sim::GraspClosing closing;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw UsageError("--closing takes NAME=VALUE,..., not '" + item + "'");
    try {
      sim::set_closing_factor(closing, item.substr(0, eq),
                              parse_number(item.substr(eq + 1), "--closing " + item.substr(0, eq)));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--closing: ") + e.what());
    }
  }
  return closing;
}

// The tracker jitter of a recording: retargeted by Naive (its angles as tracked) onto the study
// hand, less the poses' moving average over 0.1 s.
std::shared_ptr<const sim::PoseJitter> recording_jitter(const std::string& path) {
  const retarget::RecordingPoses poses =
      retarget::retarget_recording(tracking::read_recording(path), retarget::Strategy::kNaive);
  return std::make_shared<const sim::PoseJitter>(sim::pose_jitter(poses.times, poses.poses, 0.1));
}

void write_pinch_measures(util::JsonWriter& json, const sim::PinchReport& r) {
  json.field("held", r.held)
      .field("released", r.released)
      .field("lift_m", r.lift)
      .field("slip_mm", r.slip_mm)
      .field("max_penetration_mm", r.max_penetration_mm)
      .field("peak_grip_n", r.peak_grip_n)
      .field("turn_deg", r.turn_deg)
      .field("top_load_before_closing_n", r.top_load_before_closing_n)
      .field("inverted_tets", r.inverted_tets);
}

std::vector<double> cube_sides(const Arguments& args) {
  std::vector<double> cubes;
  for (const std::string& c : args.all("cube")) {
    const double side = parse_number(c, "--cube");
    if (!(side >= 0.005 && side <= 0.1))
      throw UsageError("--cube must be between 0.005 and 0.1 m, not " + c);
    cubes.push_back(side);
  }
  if (cubes.empty()) cubes = {0.01, 0.06};
  return cubes;
}

OptionSpec physics_option() {
  return {"physics", "NAME=VALUE",
          "change a simulator parameter (SI units; docs/simulator.md), e.g. "
          "tracking_force_limit=5 or cube_floor_stiffness=1e5; repeatable",
          "", true};
}

OptionSpec posture_option() {
  return {"posture", "solved|functional",
          "how each pinch is placed: the pads' inverse kinematics with the wrist's turn fixed "
          "(solved), or the wrist free and the thumb and index drawn towards a functional "
          "posture (functional; docs/simulator.md)",
          "solved"};
}

sim::PinchPosture posture_of(const Arguments& args) {
  return sim::parse_pinch_posture(args.choice("posture", {"solved", "functional"}));
}

void apply_physics_option(const Arguments& args, sim::SimParameters& parameters) {
  for (const std::string& item : args.all("physics")) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw UsageError("--physics takes NAME=VALUE, not '" + item + "'");
    try {
      sim::set_sim_parameter(parameters, item.substr(0, eq),
                             parse_number(item.substr(eq + 1), "--physics " + item.substr(0, eq)));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--physics: ") + e.what());
    }
  }
}

void write_physics(util::JsonWriter& json, const std::vector<std::string>& physics) {
  json.key("physics").begin_array();
  for (const std::string& item : physics) json.value(item);
  json.end_array();
}

std::vector<OptionSpec> sim_grasp_options() {
  std::vector<OptionSpec> specs = {
      {"cube", "METRES", "a cube's side; repeatable (default: 0.01 and 0.06, the study's)", "",
       true},
      {"factor", "NAME",
       "map only this factor of the closing; repeatable (default: every one: over_closure, "
       "tilt_yaw, tilt_pitch, offset_along, lead, closing_speed, lift_acceleration, hold, and "
       "jitter with "
       "--jitter-from)",
       "", true},
      {"closing", "NAME=VALUE,...",
       "run this closing instead of the grid, in the factors' units (mm, deg, side, ms, cm/s, "
       "m/s2, s), e.g. over_closure=20,lead=100; repeatable, each closing's repeats the same as "
       "run alone",
       "", true},
      {"grid", "single|pairs|none",
       "each factor alone at its levels, or every pair of factors at about half their ranges "
       "(docs/simulator.md), or no grid",
       "single"},
      {"draws", "N", "also run N closings drawn from the distribution of people's closings", "0"},
      {"seed", "S", "the draws' seed, and the repeats' cubes'", "1"},
      {"jitter-from", "RECORDING",
       "lay this recording's tracker jitter on the closings: the jitter factor in the grid, "
       "its own jitter in the draws (e.g. data/leap/pinch.json.lz); reports what each of the "
       "factor's levels does at the scripted pinch's pads"},
      {"repeats", "K",
       "run each closing K times: as given, then with the cube moved along the floor by up to "
       "0.1 mm from where the hand aims; reports how many closings were held in every repeat, "
       "in none and in some (docs/simulator.md)",
       "1"},
      {"jobs", "J", "closings run side by side (default: the machine's cores)", "0"},
      posture_option(),
      {"json", "OUT", "write every closing's outcome as JSON (- for standard output)"},
      {"against", "BEFORE.json",
       "set each closing beside the same closing of a map sim grasp --json wrote before (other "
       "physics, another time step): which it held there and loses here, and the other way; with "
       "repeats, each closing's hold rate before and now, and those that changed by more than "
       "the repeats resolve"},
  };
  specs.push_back(physics_option());
  return specs;
}

CommandHelp sim_grasp_help() {
  return {"sim grasp",
          {"[cube] [grid] [factor] [draws] [seed] [jitter-from] [physics] [posture] [repeats] "
           "[jobs] [against] [json]",
           "[cube] closing [jitter-from] [physics] [posture] [repeats] [against] [json]"},
          "The soft hand pinches each cube, lifts it 10 cm, holds it and opens, closing as the "
          "closing says on the intermediate hand it follows: each pad's target past its face "
          "(over_closure, mm), the pinch's axis turned about the vertical and the faces' "
          "horizontal (tilt_yaw, tilt_pitch, degrees), the pads moved along the faces "
          "(offset_along, of the side), one digit first (lead, ms: the thumb before the index; "
          "below 0 after), the closing's speed (closing_speed, cm/s of each pad), the lift's "
          "peak acceleration (lift_acceleration, m/s2), the hold (hold, s) and a real "
          "recording's tracker jitter laid on the hand (jitter, times it; --jitter-from). The "
          "grid runs each factor alone at its levels from the scripted pinch (sim pinch), or "
          "pairs of factors; --draws adds closings drawn from a distribution of people's "
          "closings whose sources --json lists. Reports per closing whether the cube was held "
          "through the lift and hold and released, its slip between the pads, the flesh's "
          "deepest penetration, the hold's peak grip and the cube's turn, how a lost run lost it, "
          "and (--json) how much later the index's pad first touched it than the thumb's; the "
          "hold rate per factor and over the draws with its 95 % interval, and how many of the "
          "grid's closings within half of every factor's range it held; with --repeats, how many "
          "closings it held every time, never and only sometimes (docs/simulator.md)."};
}

int sim_grasp(const std::vector<std::string>& argv) {
  const Arguments args(sim_grasp_options(), argv);
  if (args.help_requested()) return print_help(sim_grasp_help(), args);
  const std::vector<double> cubes = cube_sides(args);
  const std::string grid = args.choice("grid", {"single", "pairs", "none"});
  const long draws = args.integer("draws");
  if (draws < 0) throw UsageError("--draws must be 0 or more");
  const std::uint64_t seed = args.seed("seed");
  std::shared_ptr<const sim::PoseJitter> jitter;
  if (args.has("jitter-from")) jitter = recording_jitter(args.text("jitter-from"));
  const std::vector<sim::ClosingPoint> grid_points = grid_of(args, grid, draws, jitter != nullptr);
  for (const sim::ClosingPoint& p : grid_points)
    if (p.closing.jitter > 0 && !jitter)
      throw UsageError("a closing with jitter needs --jitter-from RECORDING");
  if (grid_points.empty() && draws == 0) throw UsageError("--grid none needs --draws N");
  const long repeats = args.integer("repeats");
  if (repeats < 1 || repeats > 100) throw UsageError("--repeats must be from 1 to 100");
  const int jobs = job_count(args);
  const bool to_stdout = args.text("json") == "-";
  std::vector<MappedCube> before;
  if (args.has("against")) before = read_grasp_map(args.text("against"));
  std::vector<CubeMap> maps;
  const auto start = std::chrono::steady_clock::now();
  sim::SimParameters parameters;
  apply_physics_option(args, parameters);
  const sim::PinchPosture posture = posture_of(args);
  for (double side : cubes) {
    std::vector<sim::ClosingPoint> points = grid_points;
    for (sim::ClosingPoint& p :
         sim::human_closing_draws(int(draws), seed, side, jitter ? 1.0 : 0.0))
      points.push_back(std::move(p));
    points = sim::repeated_closings(points, int(repeats), seed);
    sim::PinchScene scene =
        sim::make_pinch_scene(side, 1, 0.003, hand::HandShape{}.length, parameters, posture);
    scene.jitter = jitter;
    CubeMap map = map_cube(scene, side, points, jobs, to_stdout, start);
    map.repeats = int(repeats);
    if (jitter) map.pad_jitter = jitter_at_pads(scene, *jitter);
    if (args.has("against")) {
      map.against = compare_with(before, map);
      map.against_missing = !map.against;
    }
    if (!to_stdout) {
      if (jitter && maps.empty())
        std::printf("jitter of %s: the wrist %.2f mm, the joints %.2f deg RMS\n",
                    args.text("jitter-from").c_str(), 1000 * jitter->root_rms(),
                    jitter->angle_rms() * 180 / M_PI);
      if (posture == sim::PinchPosture::kFunctional && maps.empty())
        std::printf("each pinch placed in the functional posture (docs/simulator.md)\n");
      print_map(map);
    }
    maps.push_back(std::move(map));
  }
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_map_json(
          maps, {int(draws), seed, args.all("physics"), args.text("jitter-from"), jitter, posture},
          out);
    });
  return 0;
}

}  // namespace handlab::cli
