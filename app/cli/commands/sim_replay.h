// handlab-cli sim replay: the soft hand driven by a real recording (sim_replay.cpp).
#pragma once

#include <string>
#include <vector>

#include "app/cli/command_help.h"

namespace handlab::cli {

int sim_replay(const std::vector<std::string>& argv);
// Its option table and help (the sim family lists every usage).
std::vector<OptionSpec> sim_replay_options();
CommandHelp sim_replay_help();

}  // namespace handlab::cli
