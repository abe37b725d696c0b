// The simulator's scalar parameters by name (SimParameters' field names), so that a command
// can change one to measure what it does (`sim pinch --physics`, `sim grasp --physics`).
#pragma once

#include <string>
#include <vector>

#include "core/sim/hand_sim_model.h"

namespace handlab::sim {

// The names a parameter can be set by.
std::vector<std::string> sim_parameter_names();

// Sets the parameter `name` to `value` (SI units); throws std::invalid_argument naming the
// parameters for an unknown name, or for a value the parameter cannot take (negative, or
// below a positive minimum).
void set_sim_parameter(SimParameters& parameters, const std::string& name, double value);

}  // namespace handlab::sim
