// The grasps of a study's logged trials counted by what they met the cube with: how many were
// dropped of those whose thumb (or index) met it with its tip, its pad or its base, and of
// those pinched near or far from the cube's centre; per cube size (what a participant sees)
// or per condition. `handlab-cli grasps` prints and writes them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/util/json_writer.h"
#include "studies/analysis/grasp_contacts.h"

namespace handlab::studies {

struct GraspCount {
  int grasps = 0, dropped = 0;
};

// The pinch's distance from the cube's centre along the floor, as a share of the cube's side.
inline constexpr std::array<double, 2> kPinchOffsetBounds = {0.2, 0.4};

struct GraspTally {
  std::string group;  // "6 cm" (by cube) or the condition's label
  double cube_size = 0.0;
  int trials = 0, grasps = 0, placed = 0, dropped = 0, caught_again = 0, unfinished = 0;
  std::array<GraspCount, 3> by_thumb{}, by_index{};  // indexed by PhalanxPart
  std::array<GraspCount, 3> by_offset{};             // below, between and above kPinchOffsetBounds
};

enum class GraspGrouping { kCube, kCondition };

// In the order the groups first appear.
std::vector<GraspTally> tally_grasps(const std::vector<TrialGrasps>& trials,
                                     GraspGrouping grouping);

// {"trials", "groups": [tally...], "grasps": [one per grasp]} into a writer at a value.
void write_grasps_json(util::JsonWriter& w, const std::vector<TrialGrasps>& trials,
                       const std::vector<GraspTally>& tallies);

}  // namespace handlab::studies
