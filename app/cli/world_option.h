// The --world option of every command that simulates trials: one default, one description.
#pragma once

#include <string>

#include "app/cli/arguments.h"
#include "studies/session/trial_driver.h"

namespace handlab::cli {

// proxy: what a user runs first (a 20-person study in seconds); soft: the study's physics,
// minutes a participant (docs/performance.md).
inline OptionSpec world_option() {
  return {"world", "proxy|soft",
          "the hand-cube physics: proxy, the grasp proxy (the cube attaches to a pinch; a "
          "20-person study takes seconds) or soft, the soft-hand simulator the study uses "
          "(contact and friction; about half a minute a participant on two cores)",
          "proxy"};
}

inline studies::WorldKind world_kind(const Arguments& args) {
  return args.choice("world", {"proxy", "soft"}) == "soft" ? studies::WorldKind::kSoftHand
                                                           : studies::WorldKind::kGraspProxy;
}

}  // namespace handlab::cli
