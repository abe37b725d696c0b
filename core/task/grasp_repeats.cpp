#include "core/task/grasp_repeats.h"

namespace handlab::sim {

std::vector<RepeatedClosing> group_by_closing(const std::vector<GraspOutcome>& outcomes) {
  std::vector<RepeatedClosing> closings;
  for (const GraspOutcome& o : outcomes) {
    if (o.point.repeat == 0 || closings.empty()) closings.push_back({&o});
    ++closings.back().runs;
    closings.back().held += o.measures.held ? 1 : 0;
  }
  return closings;
}

RepeatCounts count_repeats(const std::vector<RepeatedClosing>& closings, bool within_half) {
  RepeatCounts c;
  for (const RepeatedClosing& r : closings) {
    if (within_half && !in_half_of_grid(r.given->point)) continue;
    ++c.closings;
    (r.held == r.runs ? c.every : r.held == 0 ? c.none : c.some) += 1;
  }
  return c;
}

}  // namespace handlab::sim
