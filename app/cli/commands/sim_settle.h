// handlab-cli sim settle: a cube kicked on the floor, nothing else touching it (sim_settle.cpp).
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

int sim_settle(const std::vector<std::string>& argv);

}  // namespace handlab::cli
