// handlab-cli sim grasp: the grasp's robustness map over human-like closings (sim_grasp.cpp).
#pragma once

#include <string>
#include <vector>

#include "app/cli/arguments.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/grasp_closing.h"

namespace handlab::cli {

int sim_grasp(const std::vector<std::string>& argv);

// --closing over_closure=10,lead=100: one closing, in the factors' units (sim grasp, sim pinch);
// throws UsageError naming what is wrong.
sim::GraspClosing parse_closing_option(const std::string& text);

// --physics NAME=VALUE (repeatable): a simulator parameter changed, for sim pinch and sim grasp.
OptionSpec physics_option();
void apply_physics_option(const Arguments& args, sim::SimParameters& parameters);

}  // namespace handlab::cli
