#include "app/cli/command.h"
#include "app/cli/commands/commands.h"

namespace handlab::cli {

const std::vector<Command>& all_commands() {
  static const std::vector<Command> commands = {
      {"render", "draw the task scene offscreen into a PNG (no display needed)", run_render},
  };
  return commands;
}

}  // namespace handlab::cli
