#include "app/cli/command.h"
#include "app/cli/commands/commands.h"

namespace handlab::cli {

const std::vector<Command>& all_commands() {
  static const std::vector<Command> commands = {
      {"analyze", "repeated-measures ANOVA, post hoc, Friedman and Wilcoxon tests (R parity)",
       run_analyze},
      {"hand", "build the simulated hand (skin, flesh) or the tracked skeleton of a given size",
       run_hand},
      {"retarget", "retarget a recording onto the simulated hand (naive or ours) and report errors",
       run_retarget},
      {"tracking", "read Leap Motion recordings: info, convert to CSV or .hlrec", run_tracking},
      {"render", "draw the task scene offscreen into a PNG (no display needed)", run_render},
  };
  return commands;
}

}  // namespace handlab::cli
