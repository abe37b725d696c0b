// The grasp's robustness map: the pinch-lift-hold-release of a cube run over closings
// (grasp_closing.h) side by side, each factor alone over its levels from the scripted pinch.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/task/grasp_closing.h"
#include "core/task/pinch_loss.h"
#include "core/task/pinch_scene.h"

namespace handlab::sim {

// A closing of the map: the factor it varies from the scripted pinch ("" for the pinch itself)
// at `level` (the factor's unit).
struct ClosingPoint {
  std::string factor;
  double level = 0.0;
  GraspClosing closing;
  int repeat = 0;  // 0: the closing as specified; 1, 2, ...: its repeats (repeated_closings)
};

// Every factor of `factors` (all when empty, the jitter only `with_jitter`) alone at each of
// its levels, the others at the scripted pinch's; the scripted pinch first, once.
std::vector<ClosingPoint> single_factor_grid(const std::vector<std::string>& factors = {},
                                             bool with_jitter = false);

// Every pair of factors (the jitter only `with_jitter`) at each pair of their pair_levels, the
// others at the scripted pinch's; factor "pair", level the closing's number (1, 2, ...).
std::vector<ClosingPoint> factor_pairs_grid(bool with_jitter = false);

// A grid's closing (not a draw) within half of every factor's range (grasp_closing.h): the
// part of the map the grip must hold whole.
bool in_half_of_grid(const ClosingPoint& point);

// How far a repeat moves the cube from where the hand aims (m): a disc of this radius.
constexpr double kRepeatShift = 1e-4;

// Each point `repeats` times: as it is, then repeats 1, 2, ... with the cube moved along the
// floor to a point drawn evenly from the disc of radius kRepeatShift (GraspClosing::
// cube_shift_x, _z), the same for the same seed, closing (its factor, level and values) and
// repeat. A closing held in some repeats and lost in others turns on a detail no hand controls
// (grasp_repeats.h counts them).
std::vector<ClosingPoint> repeated_closings(const std::vector<ClosingPoint>& points, int repeats,
                                            std::uint64_t seed);

struct GraspOutcome {
  ClosingPoint point;
  PinchReport measures;         // as sim pinch judges them (pinch_script.h)
  double pinch_error_mm = 0.0;  // how far the closed pose misses the pads' targets (IK)
  // The pinch's placement (pinch_script.h): the other skin's nearest to the cube or the column
  // under it (mm, below 0 inside) and the pads' from their goals on the faces (mm), whether the
  // pinch's rule placed the hand and met the rule.
  double pinch_clearance_mm = 0.0, placement_pad_error_mm = 0.0;
  bool placed_by_rule = false, meets_pinch_rule = false;
  double open_clearance_mm = 0.0;  // the open pose's nearest skin to the cube or its column (mm)
  // How a lost run lost the cube, and the signs it is told by (pinch_loss.h); how long after
  // the thumb's distal skin first touched the cube the index's did, and the cube's turn then
  // (none: one never did before the lift).
  PinchLoss loss = PinchLoss::kNone;
  double pushed_mm = 0.0, grip_at_lift_n = 0.0;
  std::optional<double> touch_lead_ms, turn_at_touch_deg;
};

// Runs each point on `scene`'s hand and cube (and its jitter), placed in its script's posture,
// `jobs` at once (each on one thread of the simulator), each distinct placement once first
// (same_placement, pinch_script.h); the closings placed as the scripted pinch take the scene's
// own script where it is that placement (PinchScript::scripted_placement). `placed` is called
// with the count of placements made and the number to make after each (never where the scene's
// is the only one), `done` with the count of runs finished after each, under a lock, from the
// worker thread that finished it.
std::vector<GraspOutcome> run_grasp_map(
    const PinchScene& scene, const std::vector<ClosingPoint>& points, int jobs,
    const std::function<void(int done)>& done = {},
    const std::function<void(int placed, int to_place)>& placed = {});

}  // namespace handlab::sim
