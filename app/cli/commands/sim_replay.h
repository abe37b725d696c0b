// handlab-cli sim replay: the soft hand driven by a real recording (sim_replay.cpp).
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

int sim_replay(const std::vector<std::string>& argv);

}  // namespace handlab::cli
