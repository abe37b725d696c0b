#include "core/task/grasp_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/parallel_runs.h"
#include "core/util/portable_random.h"

namespace handlab::sim {

std::vector<ClosingPoint> single_factor_grid(const std::vector<std::string>& factors,
                                             bool with_jitter) {
  std::vector<ClosingPoint> points = {{"", 0.0, GraspClosing{}}};
  for (const ClosingFactor& f : closing_factors()) {
    if (!factors.empty() && std::find(factors.begin(), factors.end(), f.name) == factors.end())
      continue;
    if (factors.empty() && f.name == "jitter" && !with_jitter) continue;
    for (double level : f.levels) {
      GraspClosing closing;
      set_closing_factor(closing, f.name, level);
      points.push_back({f.name, level, closing});
    }
  }
  return points;
}

std::vector<ClosingPoint> factor_pairs_grid(bool with_jitter) {
  std::vector<ClosingFactor> factors;
  for (const ClosingFactor& f : closing_factors())
    if (with_jitter || f.name != "jitter") factors.push_back(f);
  std::vector<ClosingPoint> points;
  for (std::size_t a = 0; a < factors.size(); ++a)
    for (std::size_t b = a + 1; b < factors.size(); ++b)
      for (double x : factors[a].pair_levels)
        for (double y : factors[b].pair_levels) {
          GraspClosing closing;
          set_closing_factor(closing, factors[a].name, x);
          set_closing_factor(closing, factors[b].name, y);
          points.push_back({"pair", double(points.size() + 1), closing});
        }
  return points;
}

bool in_half_of_grid(const ClosingPoint& point) {
  return point.factor != "draw" && within_half_of_ranges(point.closing);
}

std::vector<ClosingPoint> repeated_closings(const std::vector<ClosingPoint>& points, int repeats,
                                            std::uint64_t seed) {
  std::vector<ClosingPoint> out;
  for (const ClosingPoint& given : points) {
    // Seeded by what the closing is, not where it stands in the list: the same closing's
    // repeats move the cube alike in any grid, and --against finds them.
    const std::uint64_t closing_seed = util::fnv1a64(
        given.factor + " " + std::to_string(given.level) + " " + describe(given.closing));
    for (int r = 0; r < repeats; ++r) {
      ClosingPoint p = given;
      p.repeat = r;
      if (r > 0) {
        util::PortableRandom random(
            util::splitmix64(seed ^ util::splitmix64(closing_seed + std::uint64_t(r))));
        const double radius = kRepeatShift * std::sqrt(random.uniform());
        const double angle = 2 * M_PI * random.uniform();
        p.closing.cube_shift_x = radius * std::cos(angle);
        p.closing.cube_shift_z = radius * std::sin(angle);
      }
      out.push_back(p);
    }
  }
  return out;
}

std::vector<GraspOutcome> run_grasp_map(
    const PinchScene& scene, const std::vector<ClosingPoint>& points, int jobs,
    const std::function<void(int done)>& done,
    const std::function<void(int placed, int to_place)>& placed) {
  // Each placement once: the repeats, and the closings that differ only in their timing, lift,
  // hold or jitter, share theirs (a placement by the pinch's rule is a long least squares).
  std::vector<std::size_t> placement_of(points.size()), placed_from;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::size_t k = 0;
    while (k < placed_from.size() &&
           !same_placement(points[placed_from[k]].closing, points[i].closing))
      ++k;
    if (k == placed_from.size()) placed_from.push_back(i);
    placement_of[i] = k;
  }
  std::vector<PinchScript> placements(placed_from.size());
  // The scene's own pinch, where it is the scripted pinch's placement, serves the closings
  // placed as it.
  const bool scene_placed = scene.script.scripted_placement;
  std::vector<std::size_t> to_place;
  for (std::size_t k = 0; k < placements.size(); ++k)
    if (scene_placed && same_placement(points[placed_from[k]].closing, GraspClosing{}))
      placements[k] = scene.script;
    else
      to_place.push_back(k);
  util::run_in_parallel(
      to_place.size(), jobs,
      [&](std::size_t j) {
        const std::size_t k = to_place[j];
        placements[k] = place_grasp(scene.skeleton, scene.model, points[placed_from[k]].closing,
                                    scene.script.posture);
      },
      [&](int made) {
        if (placed) placed(made, int(to_place.size()));
      });
  std::vector<GraspOutcome> outcomes(points.size());
  SimOptions options;
  if (jobs > 1) options.threads = 1;  // the runs side by side, not each one's work
  util::run_in_parallel(
      points.size(), jobs,
      [&](std::size_t i) {
        const PinchScript script = time_grasp(placements[placement_of[i]], scene.skeleton,
                                              points[i].closing, scene.jitter);
        GraspOutcome& o = outcomes[i];
        o.point = points[i];
        PinchLossWatch watch(scene.model, script);
        o.measures = run_pinch(scene.model, scene.skeleton, script, options, 0.0,
                               [&](const HandSimState& s) { watch.observe(s); });
        o.loss = watch.loss(o.measures.held);
        o.pushed_mm = watch.pushed_mm();
        o.grip_at_lift_n = watch.grip_at_lift_n();
        o.touch_lead_ms = watch.touch_lead_ms();
        o.turn_at_touch_deg = watch.turn_at_touch_deg();
        o.pinch_error_mm = 1000 * script.pinch_error;
        o.pinch_clearance_mm = 1000 * script.pinch_clearance;
        o.placement_pad_error_mm = 1000 * script.placement_pad_error;
        o.open_clearance_mm = 1000 * script.open_clearance;
        o.placed_by_rule = script.placed_by_rule;
        o.meets_pinch_rule = script.pinch_meets_rule;
      },
      done);
  return outcomes;
}

}  // namespace handlab::sim
