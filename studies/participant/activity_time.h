// Where a simulated participant's time goes: the seconds of a trial spent in each of its
// activities (reaching, coming down, closing, ...), as its own state machine lived them, and
// the attempts that ended in a re-grasp. Pooled over trials by the cube it saw, the one thing
// that tells its trials apart (never the condition): what a study's trials are made of, and
// where a slower or failing trial spent its time.
#pragma once

#include <array>
#include <cstddef>

namespace handlab::studies {

enum class Activity {
  kReact,      // waiting for the go, its reaction time
  kReach,      // to over the cube, with its corrective submovements and the looks after them
  kDescend,    // down to the grasp point, and the look at the bottom
  kClose,      // closing until both pads are on the cube, and the dwell that confirms it
  kLift,       // lifting, and the look that checks the cube came up
  kTransport,  // to over B, with its corrections
  kSetDown,    // lowering, letting go, and waiting for the cube to rest
  kWithdraw,   // up and away, then watching the cube it left until the trial ends
  kReopen,     // re-opening after a missed closing, a slip or a cube at rest outside B
  kFreeCube,   // a cube caught on the hand: opening wide, wiping it off on the floor
};
inline constexpr std::size_t kActivityCount = 10;
static_assert(std::size_t(Activity::kFreeCube) + 1 == kActivityCount);

// The column's name in tables and JSON ("react", "reach", ..., "free_cube").
inline const char* activity_name(Activity a) {
  static const char* const names[kActivityCount] = {"react",  "reach",     "descend",  "close",
                                                    "lift",   "transport", "set_down", "withdraw",
                                                    "reopen", "free_cube"};
  return names[std::size_t(a)];
}

struct ActivityTime {
  int trials = 0;
  std::array<double, kActivityCount> seconds{};  // by Activity
  // Closings that ended with the hand shut and no cube between the pads, and cubes it saw
  // slip from the pads while lifted, carried or lowered: each was followed by a re-grasp.
  int missed_closings = 0, slips = 0;

  double& operator[](Activity a) { return seconds[std::size_t(a)]; }
  double operator[](Activity a) const { return seconds[std::size_t(a)]; }
  double total() const {
    double sum = 0.0;
    for (double s : seconds) sum += s;
    return sum;
  }
  ActivityTime& operator+=(const ActivityTime& o) {
    trials += o.trials;
    for (std::size_t k = 0; k < kActivityCount; ++k) seconds[k] += o.seconds[k];
    missed_closings += o.missed_closings;
    slips += o.slips;
    return *this;
  }
};

}  // namespace handlab::studies
