// handlab-cli simulate: a whole study run by simulated participants, headless.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/commands/simulate_slurm.h"
#include "app/cli/commands/step_parts.h"
#include "app/cli/progress_line.h"
#include "app/cli/world_option.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "studies/analysis/condition_outcomes.h"
#include "studies/protocol/protocol.h"
#include "studies/simulate/simulated_study.h"

namespace handlab::cli {

namespace {

// The frozen model with `NAME=VALUE` changes (simulate --set).
studies::ParticipantModel model_with_changes(const std::vector<std::string>& settings) {
  std::vector<std::pair<std::string, double>> changes;
  for (const std::string& s : settings) {
    const std::size_t equals = s.find('=');
    char* end = nullptr;
    const double value =
        equals == std::string::npos ? 0.0 : std::strtod(s.c_str() + equals + 1, &end);
    if (equals == std::string::npos || end == s.c_str() + equals + 1 || *end != '\0')
      throw UsageError("--set takes NAME=VALUE (a number), not '" + s + "'");
    changes.emplace_back(s.substr(0, equals), value);
  }
  try {
    return studies::changed_model(studies::frozen_participant_model(), changes);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--set: ") + e.what());
  }
}

// Where the participants' time went: seconds a trial in each activity, and the re-grasps'
// causes a trial, a column per cube they saw (never per condition: what they can tell apart).
void print_participant_time(const studies::SimulationReport& report) {
  if (report.participant_time.empty()) return;
  std::cout << "\n" << std::left << std::setw(20) << "participants' time" << std::right;
  for (const auto& [cube, t] : report.participant_time)
    std::cout << std::setw(7) << std::setprecision(1) << 100.0 * cube << " cm";
  std::cout << "   (s a trial, every trial, by the cube seen)\n";
  auto row = [&](const char* name, auto value) {
    std::cout << std::left << std::setw(20) << name << std::right << std::setprecision(2);
    for (const auto& [cube, t] : report.participant_time)
      std::cout << std::setw(10) << value(t) / std::max(1, t.trials);
    std::cout << "\n";
  };
  for (std::size_t k = 0; k < studies::kActivityCount; ++k)
    row(studies::activity_name(studies::Activity(k)), [k](const auto& t) { return t.seconds[k]; });
  row("total", [](const auto& t) { return t.total(); });
  row("missed closings", [](const auto& t) { return double(t.missed_closings); });
  row("slips", [](const auto& t) { return double(t.slips); });
}

void write_participant_time(util::JsonWriter& w, const studies::SimulationReport& report) {
  w.key("participant_time").begin_array();
  for (const auto& [cube, t] : report.participant_time) {
    w.begin_object().field("cube_m", cube).field("trials", t.trials).key("seconds").begin_object();
    for (std::size_t k = 0; k < studies::kActivityCount; ++k)
      w.field(studies::activity_name(studies::Activity(k)), t.seconds[k]);
    w.end_object().field("missed_closings", t.missed_closings).field("slips", t.slips).end_object();
  }
  w.end_array();
}

// The participants' indices (0-based) that --shard K/M or --only ID,... name (empty: all).
std::vector<int> shard_members(const Arguments& args, int participants) {
  std::vector<int> members;
  if (args.has("shard") && args.has("only")) throw UsageError("give --shard or --only, not both");
  if (args.has("shard")) {
    const std::string text = args.text("shard");
    int k = 0, m = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &k, &m, &rest) != 2 || m < 1 || k < 1 || k > m)
      throw UsageError("--shard takes K/M with 1 <= K <= M, not '" + text + "'");
    if (m > participants) throw UsageError("--shard: more shards than participants");
    for (int i = k - 1; i < participants; i += m) members.push_back(i);
  }
  if (args.has("only")) {
    std::string list = args.text("only") + ",";
    for (std::size_t at = 0, comma; (comma = list.find(',', at)) != std::string::npos;
         at = comma + 1) {
      const std::string id = list.substr(at, comma - at);
      int index = 0;
      while (index < participants && studies::simulated_participant_id(index) != id) ++index;
      if (index == participants)
        throw UsageError("--only: '" + id + "' is not a participant of a study of " +
                         std::to_string(participants) + " (S01 ...)");
      if (std::find(members.begin(), members.end(), index) != members.end())
        throw UsageError("--only: " + id + " named twice");
      members.push_back(index);
    }
  }
  return members;
}

}  // namespace

namespace {

std::vector<OptionSpec> simulate_options() {
  std::vector<OptionSpec> specs = {
      {"protocol", "FILE", "the study protocol (JSON, docs/study.md)"},
      {"participants", "N", "how many simulated participants to enrol", "20"},
      {"seed", "S", "the population seed: the same seed gives the same database content", "0"},
      {"db", "OUT", "the study database to create (must not exist)"},
      {"jobs", "J", "sessions run side by side (threads; default: the machine's cores)", "0"},
      world_option(),
      {"shard", "K/M",
       "run only the K-th of M shards (participants K, K+M, K+2M, ...), each at its place in "
       "the whole study; `merge` joins the shards into the study a single run makes"},
      {"only", "ID,...", "run only these participants (S01, S02, ...) of the study"},
      {"frames", "", "store every trial's frames (about 160 kB a simulated second)"},
      {"set", "NAME=VALUE",
       "change a parameter of the participant model, for a sensitivity analysis: a per-person "
       "parameter's mean, a fixed one's or a behaviour constant's value (SI units; the names "
       "are the JSON keys of docs/simulated-participants.md's table); the model's hash "
       "changes with it; repeatable",
       "", true},
      {"slurm", "DIR",
       "instead of running here, write the study as Slurm batch jobs into DIR and submit them "
       "with sbatch: a job array (a task a shard) and a merge job after it (docs/cluster.md)"},
      {"studies", "K", "with --slurm: a series of K studies, seeds S ... S+K-1", "1"},
      {"status", "DIR",
       "say which parts of the series in DIR are done, running, stopped or missing, and how "
       "to rerun them (reads the files, not squeue)"},
      {"quiet", "", "no progress line"},
      {"json", "OUT", "write the outcome per condition as JSON (- for standard output)"},
  };
  // The Slurm settings after --studies.
  const auto after_studies = std::find_if(specs.begin(), specs.end(),
                                          [](const OptionSpec& o) { return o.name == "studies"; });
  const std::vector<OptionSpec> slurm_specs = slurm_option_specs();
  specs.insert(after_studies + 1, slurm_specs.begin(), slurm_specs.end());
  return specs;
}

CommandHelp simulate_help() {
  return {"simulate",
          {"protocol [participants] [seed] db [jobs] [world] [shard|only] [frames] [set] [json]",
           "protocol [participants] [seed] slurm [studies] [per-task] [dry-run] [options]",
           "status [json]"},
          "Enrols N participants drawn from the study population (covariates stored like real "
          "ones, marked simulated) and runs every session with the closed-loop participant model "
          "(docs/simulated-participants.md): its own tracked hand -> retargeting -> physics -> "
          "task, questionnaires answered from what it experienced. On a Slurm cluster, the study "
          "(or a series) as a job array of shards and a merge job (docs/cluster.md)."};
}

}  // namespace

namespace {

// The study's options from the command line, checked.
studies::SimulationOptions simulation_options(const Arguments& args) {
  studies::SimulationOptions options;
  options.participants = int(args.integer("participants"));
  if (options.participants < 1 || options.participants > 10000)
    throw UsageError("--participants must be between 1 and 10000");
  options.seed = args.seed("seed");
  options.only = shard_members(args, options.participants);
  options.jobs = job_count(args);
  options.world = world_kind(args);
  options.frames = args.flag("frames");
  options.model = model_with_changes(args.all("set"));
  return options;
}

// --slurm: the series of --studies studies from --seed on, as Slurm jobs.
void submit_series(const Arguments& args, const studies::SimulationOptions& options) {
  studies::SlurmSeries series = series_settings(args);
  const long count = args.integer("studies");
  if (count < 1 || count > 100000) throw UsageError("--studies must be between 1 and 100000");
  for (long k = 0; k < count; ++k)
    series.studies.push_back({options.participants, options.seed + std::uint64_t(k)});
  series.simulate_options = {"--world", args.text("world")};
  if (options.frames) series.simulate_options.push_back("--frames");
  for (const std::string& s : args.all("set")) {
    series.simulate_options.push_back("--set");
    series.simulate_options.push_back(s);
  }
  submit_slurm_series(series, args.flag("dry-run"));
}

// Where the time went: the soft hand's steps, all trials (practice included).
void print_simulator_totals(const studies::SimulationReport& report) {
  sim::StepTotals all;
  for (const auto& [label, t] : report.simulator) all += t;
  if (all.steps == 0) return;
  std::cout << "\n"
            << std::left << std::setw(16) << "soft hand" << std::right << std::setw(10) << "steps"
            << std::setw(12) << "factorising" << std::setw(9) << "passes" << std::setw(6) << "CG"
            << std::setw(12) << "ms a step\n";
  auto line = [](const std::string& what, const sim::StepTotals& t) {
    const double steps = double(std::max(1L, t.steps));
    std::cout << std::left << std::setw(16) << what << std::right << std::setw(10) << t.steps
              << std::setw(11) << std::setprecision(1) << 100.0 * t.factorizing_steps / steps << "%"
              << std::setw(9) << std::setprecision(2) << t.passes / steps << std::setw(6)
              << std::setprecision(2) << t.linear_iterations / steps << std::setw(11)
              << std::setprecision(2) << 1000.0 * t.seconds / steps << "\n";
  };
  for (const auto& [label, t] : report.simulator) line(label, t);
  line("all", all);
  print_step_parts(std::cout, all);
}

void print_outcome(const studies::SimulationReport& report,
                   const studies::SimulationOptions& options, const Arguments& args) {
  std::cout << report.participants << " simulated participants, " << report.trials << " trials ("
            << report.completed << " completed, " << report.timeouts << " timed out) in "
            << std::fixed << std::setprecision(1) << report.seconds << " s for "
            << report.simulated_seconds << " s of trials; " << args.text("db") << "\n"
            << studies::kParticipantModelVersion << ", parameters sha256 "
            << studies::model_sha256(options.model)
            << (args.all("set").empty() ? "" : " (changed by --set)") << "\n\n";
  std::cout << std::left << std::setw(16) << "condition" << std::right << std::setw(8) << "trials"
            << std::setw(11) << "completed" << std::setw(9) << "success" << std::setw(9)
            << "timeout" << std::setw(12) << "mean time" << std::setw(8) << "drops\n";
  for (const studies::ConditionOutcome& c : report.conditions)
    std::cout << std::left << std::setw(16) << c.condition << std::right << std::setw(8)
              << c.planned << std::setw(11) << c.completed << std::setw(8) << std::setprecision(1)
              << (c.planned ? 100.0 * c.completed / c.planned : 0.0) << "%" << std::setw(9)
              << c.timeouts << std::setw(10) << std::setprecision(2) << c.mean_time_s << " s"
              << std::setw(7) << c.drops << "\n";
  print_participant_time(report);
  print_simulator_totals(report);
}

void write_outcome_json(std::ostream& out, const studies::SimulationReport& report,
                        const studies::SimulationOptions& options, const Arguments& args) {
  util::JsonWriter w(out);
  w.begin_object()
      .field("db", args.text("db"))
      .field("participants", report.participants)
      .field("seed", options.seed)
      .field("jobs", options.jobs)
      .field("world", args.text("world"))
      .field("model", studies::kParticipantModelVersion)
      .field("model_sha256", studies::model_sha256(options.model))
      .field("trials", report.trials)
      .field("completed", report.completed)
      .field("timeouts", report.timeouts)
      .field("seconds", report.seconds)
      .field("simulated_seconds", report.simulated_seconds)
      .key("conditions")
      .begin_array();
  // The shared keys, and `trials` (the scheduled trials: simulate's name for planned).
  for (const studies::ConditionOutcome& c : report.conditions) {
    w.begin_object();
    studies::write_condition_outcome_fields(w, c);
    w.field("trials", c.planned).end_object();
  }
  w.end_array().key("simulator").begin_array();
  for (const auto& [label, t] : report.simulator) {
    w.begin_object()
        .field("condition", label)
        .field("steps", static_cast<long long>(t.steps))
        .field("factorizing_steps", static_cast<long long>(t.factorizing_steps))
        .field("factorizations", static_cast<long long>(t.factorizations))
        .field("passes", static_cast<long long>(t.passes))
        .field("linear_iterations", static_cast<long long>(t.linear_iterations))
        .field("direct_solves", static_cast<long long>(t.direct_solves))
        .field("halvings", static_cast<long long>(t.halvings))
        .field("seconds", t.seconds);
    write_step_parts(w, t);
    w.end_object();
  }
  w.end_array();
  write_participant_time(w, report);
  w.end_object();
  out << "\n";
}

}  // namespace

int run_simulate(const std::vector<std::string>& argv) {
  const Arguments args(simulate_options(), argv);
  if (args.help_requested()) return print_help(simulate_help(), args);
  if (args.has("status")) {
    print_series_status(args.text("status"), args.has("json") ? args.text("json") : "");
    return 0;
  }
  const bool slurm = args.has("slurm");
  args.require(slurm ? std::initializer_list<const char*>{"protocol"}
                     : std::initializer_list<const char*>{"protocol", "db"});
  if (slurm && (args.has("db") || args.has("shard") || args.has("only")))
    throw UsageError(
        "--slurm writes the study's parts and merges them: no --db, --shard or --only");
  if (!slurm && (args.has("studies") || has_slurm_options(args)))
    throw UsageError(
        "--studies, --per-task, --partition, --time, --mem and --dry-run go with "
        "--slurm");
  const studies::SimulationOptions options = simulation_options(args);
  const studies::Protocol protocol = studies::read_protocol(args.text("protocol"));
  if (slurm) {
    submit_series(args, options);
    return 0;
  }
  const bool quiet = args.flag("quiet") || args.text("json") == "-";
  studies::SimulationReport report;
  {
    ProgressLine progress(quiet);
    report = studies::simulate_study(
        protocol, args.text("db"), options, [&](const studies::SimulationProgress& p) {
          char text[160];
          std::snprintf(text, sizeof text, "participants %d/%d  trials %d/%d  %.0f s",
                        p.participants_done, p.participants, p.trials_done, p.trials, p.seconds);
          progress.show(p.participants_done, text);
        });
  }
  if (args.text("json") != "-") print_outcome(report, options, args);
  if (args.has("json"))
    util::write_output(args.text("json"),
                       [&](std::ostream& out) { write_outcome_json(out, report, options, args); });
  return 0;
}

}  // namespace handlab::cli
