#include "core/task/grasp_comparison.h"

#include <algorithm>
#include <cmath>

namespace handlab::sim {

bool same_closing_any_repeat(const ClosingPoint& a, const ClosingPoint& b) {
  const bool draw = a.factor == "draw";
  if (draw != (b.factor == "draw") || (draw && a.level != b.level)) return false;
  return std::all_of(closing_factors().begin(), closing_factors().end(),
                     [&](const ClosingFactor& f) {
                       return std::abs(a.closing.*(f.field) - b.closing.*(f.field)) <= 1e-9;
                     });
}

bool same_closing(const ClosingPoint& a, const ClosingPoint& b) {
  return a.repeat == b.repeat &&
         std::abs(a.closing.cube_shift_x - b.closing.cube_shift_x) <= 1e-9 &&
         std::abs(a.closing.cube_shift_z - b.closing.cube_shift_z) <= 1e-9 &&
         same_closing_any_repeat(a, b);
}

namespace {

// Each closing of `after` that `before` ran too, with both maps' runs of it counted.
std::vector<ClosingHoldCounts> count_repeats_in_both(const std::vector<MappedClosing>& before,
                                                     const std::vector<MappedClosing>& after) {
  std::vector<ClosingHoldCounts> counts;
  for (const MappedClosing& a : after) {
    auto in = [&](const ClosingHoldCounts& c) { return same_closing_any_repeat(c.point, a.point); };
    auto it = std::find_if(counts.begin(), counts.end(), in);
    if (it == counts.end()) {
      ClosingHoldCounts c{a.point};
      c.point.repeat = 0;  // the closing as given, its cube where the hand aims
      c.point.closing.cube_shift_x = c.point.closing.cube_shift_z = 0.0;
      for (const MappedClosing& b : before) {
        if (!same_closing_any_repeat(b.point, a.point)) continue;
        ++c.runs_before;
        c.held_before += b.held ? 1 : 0;
      }
      if (c.runs_before == 0) continue;
      it = counts.insert(counts.end(), c);
    }
    ++it->runs_after;
    it->held_after += a.held ? 1 : 0;
  }
  return counts;
}

bool repeated(const std::vector<MappedClosing>& map) {
  return std::any_of(map.begin(), map.end(),
                     [](const MappedClosing& m) { return m.point.repeat > 0; });
}

}  // namespace

GraspComparison compare_maps(const std::vector<MappedClosing>& before,
                             const std::vector<MappedClosing>& after) {
  GraspComparison c;
  for (const MappedClosing& a : after) {
    const auto b = std::find_if(before.begin(), before.end(), [&](const MappedClosing& m) {
      return same_closing(m.point, a.point);
    });
    if (b == before.end()) {
      ++c.only_after;
      continue;
    }
    ++c.in_both;
    c.held_before += b->held ? 1 : 0;
    c.held_after += a.held ? 1 : 0;
    c.released_before += b->held && b->released ? 1 : 0;
    c.released_after += a.held && a.released ? 1 : 0;
    if (b->held && !a.held) c.held_before_lost_after.push_back(a.point);
    if (!b->held && a.held) c.lost_before_held_after.push_back(a.point);
  }
  if (repeated(before) || repeated(after)) c.repeated = count_repeats_in_both(before, after);
  return c;
}

}  // namespace handlab::sim
