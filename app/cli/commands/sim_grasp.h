// handlab-cli sim grasp: the grasp's robustness map over human-like closings (sim_grasp.cpp).
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

int sim_grasp(const std::vector<std::string>& argv);

}  // namespace handlab::cli
