// handlab-cli sim pinches: real recordings' closings on the soft hand (sim_pinches.cpp).
#pragma once

#include <string>
#include <vector>

#include "app/cli/command_help.h"

namespace handlab::cli {

int sim_pinches(const std::vector<std::string>& argv);
// Its option table and help (the sim family lists every usage).
std::vector<OptionSpec> sim_pinches_options();
CommandHelp sim_pinches_help();

}  // namespace handlab::cli
