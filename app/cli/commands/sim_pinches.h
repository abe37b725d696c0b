// handlab-cli sim pinches: real recordings' closings on the soft hand (sim_pinches.cpp).
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

int sim_pinches(const std::vector<std::string>& argv);

}  // namespace handlab::cli
