// The simulator's scalar parameters and switches by name (SimParameters' field names), so that
// a command can change one to measure what it does (`sim pinch --physics`, `sim grasp
// --physics`).
#pragma once

#include <string>
#include <vector>

#include "core/sim/hand_sim_model.h"

namespace handlab::sim {

// The names a parameter can be set by.
std::vector<std::string> sim_parameter_names();

// Sets the parameter `name` to `value` (SI units; a switch: 1 on, 0 off); throws
// std::invalid_argument naming the parameters for an unknown name, or for a value the
// parameter cannot take (negative, below a positive minimum, a switch neither 0 nor 1).
void set_sim_parameter(SimParameters& parameters, const std::string& name, double value);

}  // namespace handlab::sim
