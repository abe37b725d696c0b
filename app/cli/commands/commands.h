// Entry points of the subcommands; each parses its own arguments.
#pragma once

#include <string>
#include <vector>

#include "analysis/power/power_analysis.h"

namespace handlab::cli {

int run_analyze(const std::vector<std::string>& args);
int run_hand(const std::vector<std::string>& args);
int run_tracking(const std::vector<std::string>& args);
int run_retarget(const std::vector<std::string>& args);
int run_sim(const std::vector<std::string>& args);
int run_render(const std::vector<std::string>& args);
int run_study(const std::vector<std::string>& args);
int run_participant(const std::vector<std::string>& args);
int run_session(const std::vector<std::string>& args);
int run_export(const std::vector<std::string>& args);
int run_grasps(const std::vector<std::string>& args);
int run_simulate(const std::vector<std::string>& args);
int run_merge(const std::vector<std::string>& args);
int run_report(const std::vector<std::string>& args);
int run_power(const std::vector<std::string>& args);
int run_replications(const std::vector<std::string>& args);
int run_sensitivity(const std::vector<std::string>& args);
int run_xr(const std::vector<std::string>& args);

// --correction auto|none|gg|hf (power, replications); UsageError otherwise.
power::SphericityCorrection sphericity_correction(const std::string& option);

}  // namespace handlab::cli
