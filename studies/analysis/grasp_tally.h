// The grasps of a study's logged trials counted by how they met the cube: how many lost it (it
// came down onto the floor out of B) of those whose thumb (or index) had its tip, its pad or
// its base nearest the cube's centre, and of those pinched near or far from that centre; per
// cube size (what a participant sees) or per condition. `handlab-cli grasps` prints and
// writes them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/util/json_writer.h"
#include "studies/analysis/grasp_contacts.h"

namespace handlab::studies {

struct GraspCount {
  int grasps = 0, lost = 0;
};

// The edges of the bins of the pinch's distance from the cube's centre along the floor, as
// shares of the cube's side: below the first, between, from the second.
inline constexpr std::array<double, 2> kPinchOffsetEdges = {0.2, 0.4};

struct GraspTally {
  std::string group;  // "6 cm" (by cube) or the condition's label
  double cube_size = 0.0;
  int trials = 0, grasps = 0;
  int placed = 0, dropped = 0, landed = 0, caught_again = 0, unfinished = 0;  // GraspOutcome
  std::array<GraspCount, 3> by_thumb{}, by_index{};         // indexed by PhalanxPart
  std::array<GraspCount, 3> by_offset{};                    // by the bins of kPinchOffsetEdges
  std::vector<LoggedClosing> kept_closings, lost_closings;  // the grasps' whose were read
  std::vector<double> jitter_root_rms, jitter_angle_rms;    // the trials' (TrialGrasps)
  int lost() const { return dropped + landed; }
};

enum class GraspGrouping { kCube, kCondition };

// In the order the groups first appear.
std::vector<GraspTally> tally_grasps(const std::vector<TrialGrasps>& trials,
                                     GraspGrouping grouping);

// {"trials", "groups": [tally...], "grasps": [one per grasp]} into a writer at a value; a
// group's "closings" and a grasp's "closing" in the grasp map's factors and units.
void write_grasps_json(util::JsonWriter& w, const std::vector<TrialGrasps>& trials,
                       const std::vector<GraspTally>& tallies);

}  // namespace handlab::studies
