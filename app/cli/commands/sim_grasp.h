// handlab-cli sim grasp: the grasp's robustness map over human-like closings (sim_grasp.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>
#include "app/cli/command_help.h"

#include "app/cli/arguments.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/grasp_closing.h"
#include "core/task/pinch_script.h"
#include "core/task/tracker_jitter.h"
#include "core/util/json_writer.h"

namespace handlab::cli {

int sim_grasp(const std::vector<std::string>& argv);
// Its option table and help (the sim family lists every usage).
std::vector<OptionSpec> sim_grasp_options();
CommandHelp sim_grasp_help();

// --closing over_closure=10,lead=100: one closing, in the factors' units (sim grasp, sim pinch);
// throws UsageError naming what is wrong.
sim::GraspClosing parse_closing_option(const std::string& text);

// The tracker jitter of a recording: retargeted by Naive (its angles as tracked) onto the study
// hand, less the poses' moving average over 0.1 s (--jitter-from of sim grasp and sim pinch).
std::shared_ptr<const sim::PoseJitter> recording_jitter(const std::string& path);

// The measures of a pinch (held, released, lift, slip, penetration, grip, turn) as fields of
// the JSON object being written: sim pinch's and each closing of sim grasp's.
void write_pinch_measures(util::JsonWriter& json, const sim::PinchReport& r);

// --cube SIDE (repeatable): the cubes' sides, 5 mm to 10 cm (default the study's, 1 and 6 cm);
// throws UsageError naming a side out of range.
std::vector<double> cube_sides(const Arguments& args);

// --physics NAME=VALUE (repeatable): a simulator parameter changed, for the sim commands.
OptionSpec physics_option();
void apply_physics_option(const Arguments& args, sim::SimParameters& parameters);
// The changes as given, "physics": [...], in the JSON object being written.
void write_physics(util::JsonWriter& json, const std::vector<std::string>& physics);

// --posture solved|functional: how sim pinch and sim grasp place each pinch (pinch_posture.h).
OptionSpec posture_option();
sim::PinchPosture posture_of(const Arguments& args);

}  // namespace handlab::cli
