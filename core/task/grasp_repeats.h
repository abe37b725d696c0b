// A repeated map's closings (sim grasp --repeats, grasp_map.h): each closing's runs together,
// and how many closings were held in every repeat, in none and in some. A closing held in some
// repeats and lost in others turns on a detail no hand controls.
#pragma once

#include <vector>

#include "core/task/grasp_map.h"

namespace handlab::sim {

// A closing's runs: the closing as given, then its repeats.
struct RepeatedClosing {
  const GraspOutcome* given = nullptr;
  int runs = 0, held = 0;
};

// The outcomes grouped by closing, in their order: a closing's repeats follow it
// (repeated_closings).
std::vector<RepeatedClosing> group_by_closing(const std::vector<GraspOutcome>& outcomes);

struct RepeatCounts {
  int closings = 0, every = 0, none = 0, some = 0;
};
// Of the closings, or of the grid's closings within half of every range (not the draws), how
// many were held in every repeat, in none and in some.
RepeatCounts count_repeats(const std::vector<RepeatedClosing>& closings, bool within_half);

}  // namespace handlab::sim
