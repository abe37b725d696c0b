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

struct GraspComparison {
  int in_both = 0;                              // closings both maps ran
  int held_before = 0, held_after = 0;          // of those
  int released_before = 0, released_after = 0;  // of those, held and released
  int only_after = 0;                           // closings of the second map the first did not run
  std::vector<ClosingPoint> held_before_lost_after, lost_before_held_after;
};

// The same closing: every factor's value within a nanometre, nanoradian or nanosecond, and,
// for the draws of people's closings (factor "draw"), the same draw; the same repeat, its cube
// moved alike.
bool same_closing(const ClosingPoint& a, const ClosingPoint& b);

// `after`'s closings matched with `before`'s (same_closing), in `after`'s order.
GraspComparison compare_maps(const std::vector<MappedClosing>& before,
                             const std::vector<MappedClosing>& after);

}  // namespace handlab::sim
