// Two runs of the grasp map side by side, closing by closing: which closings a change (of the
// physics, the time step, anything) made the grip lose or hold. A change is judged on this
// (docs/simulator.md, "Two maps side by side").
#pragma once

#include <vector>

#include "core/task/grasp_map.h"

namespace handlab::sim {

// A closing and whether a map's run held and released its cube.
struct MappedClosing {
  ClosingPoint point;
  bool held = false;
  bool released = false;
};

// A closing's runs in both maps, its repeats together (and any closing the same in every
// factor: a single grid's levels at the scripted pinch's values are the scripted pinch): how many
// each map ran and held. Near where the grip gives way a closing is held in some repeats and not
// others (the cube moved by a tenth of a millimetre), so a change is judged by how often it is
// held, not by one run.
struct ClosingHoldCounts {
  ClosingPoint point;  // as given (repeat 0)
  int runs_before = 0, held_before = 0, runs_after = 0, held_after = 0;
};

struct GraspComparison {
  int in_both = 0;                              // closings both maps ran
  int held_before = 0, held_after = 0;          // of those
  int released_before = 0, released_after = 0;  // of those, held and released
  int only_after = 0;                           // closings of the second map the first did not run
  std::vector<ClosingPoint> held_before_lost_after, lost_before_held_after;
  // Where either map repeated a closing: each closing both ran, in `after`'s order.
  std::vector<ClosingHoldCounts> repeated;
};

// The same closing in any repeat: every factor's value within a nanometre, nanoradian or
// nanosecond (a grid's closing is its factors, whichever grid ran it, under whatever name),
// and for the draws of people's closings (factor "draw") the same draw.
bool same_closing_any_repeat(const ClosingPoint& a, const ClosingPoint& b);

// The same closing (same_closing_any_repeat) in the same repeat, its cube moved alike.
bool same_closing(const ClosingPoint& a, const ClosingPoint& b);

// `after`'s closings matched with `before`'s (same_closing), in `after`'s order; with repeats
// in either, also matched whatever the repeat (same_closing_any_repeat).
GraspComparison compare_maps(const std::vector<MappedClosing>& before,
                             const std::vector<MappedClosing>& after);

}  // namespace handlab::sim
