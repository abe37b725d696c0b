// handlab-cli sim settle: a cube kicked on the floor, nothing else touching it (sim_settle.cpp).
#pragma once

#include <string>
#include <vector>

#include "app/cli/command_help.h"

namespace handlab::cli {

int sim_settle(const std::vector<std::string>& argv);
// Its option table and help (the sim family lists every usage).
std::vector<OptionSpec> sim_settle_options();
CommandHelp sim_settle_help();

}  // namespace handlab::cli
