// handlab-cli power: simulation-based power of a study design (docs/power.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <thread>

#include "analysis/power/power_analysis.h"
#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "app/cli/commands/simulate_slurm.h"
#include "app/cli/nearest_word.h"
#include "app/cli/progress_line.h"
#include "app/cli/world_option.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "studies/power/pilot_model.h"
#include "studies/power/pipeline_power.h"
#include "studies/protocol/protocol.h"
#ifdef HANDLAB_WITH_REPORT
#include "app/cli/gui_application.h"
#include "app/report/power_figure.h"
#endif

namespace handlab::cli {
namespace {

// "10:40:2" (from, to, step), "10:40" (step 1), "12,20,30" or "20".
std::vector<int> parse_n(const std::string& text) {
  std::vector<int> n;
  auto whole = [&](const std::string& s) {
    std::size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || s.empty()) throw UsageError("--n: '" + s + "' is not a whole number");
    return v;
  };
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::size_t from = 0, at;
    while ((at = text.find(':', from)) != std::string::npos) {
      parts.push_back(text.substr(from, at - from));
      from = at + 1;
    }
    parts.push_back(text.substr(from));
    if (parts.size() > 3) throw UsageError("--n takes FROM:TO[:STEP]");
    const int a = whole(parts[0]), b = whole(parts[1]),
              step = parts.size() == 3 ? whole(parts[2]) : 1;
    if (step < 1 || b < a) throw UsageError("--n: FROM:TO:STEP needs TO >= FROM and STEP >= 1");
    for (int v = a; v <= b; v += step) n.push_back(v);
  } else {
    std::size_t from = 0, at;
    while ((at = text.find(',', from)) != std::string::npos) {
      n.push_back(whole(text.substr(from, at - from)));
      from = at + 1;
    }
    n.push_back(whole(text.substr(from)));
  }
  for (int v : n)
    if (v < 3 || v > 100000) throw UsageError("--n: every N must be between 3 and 100000");
  return n;
}

void write_map(util::JsonWriter& w, const char* key,
               const std::vector<const power::PowerEstimate*>& list,
               std::vector<double> power::PowerEstimate::*field) {
  w.key(key).begin_object();
  for (const power::PowerEstimate* e : list) {
    w.key(e->name).begin_array();
    for (double v : e->*field) w.value(v);
    w.end_array();
  }
  w.end_object();
}

std::vector<const power::PowerEstimate*> pointers(const std::vector<power::PowerEstimate>& v) {
  std::vector<const power::PowerEstimate*> out;
  for (const auto& e : v) out.push_back(&e);
  return out;
}

void print_table(const power::PowerReport& r, const std::vector<power::PowerEstimate>& list,
                 const char* heading, double target) {
  std::size_t width = std::string(heading).size();
  for (const auto& e : list) width = std::max(width, e.name.size());
  std::cout << std::left << std::setw(int(width) + 2) << heading << std::right;
  for (int n : r.n) std::cout << std::setw(6) << ("N=" + std::to_string(n));
  std::cout << "   N for " << std::setprecision(2) << target << "\n";
  for (const auto& e : list) {
    std::cout << std::left << std::setw(int(width) + 2) << e.name << std::right << std::fixed
              << std::setprecision(2);
    for (double p : e.power) std::cout << std::setw(6) << p;
    const auto n = power::n_for_target(r, e, target);
    std::cout << "   " << (n ? std::to_string(*n) : std::string("-")) << "\n";
  }
  std::cout << std::defaultfloat;
}

}  // namespace

power::SphericityCorrection sphericity_correction(const std::string& option) {
  if (option == "auto") return power::SphericityCorrection::kAuto;
  if (option == "none") return power::SphericityCorrection::kNone;
  if (option == "gg") return power::SphericityCorrection::kGreenhouseGeisser;
  if (option == "hf") return power::SphericityCorrection::kHuynhFeldt;
  throw UsageError("--correction must be auto, none, gg or hf, not '" + option + "'" +
                   did_you_mean(option, {"auto", "none", "gg", "hf"}));
}

namespace {

// The pipeline's studies as a Slurm series: every study's shards, a merge, then this command
// again with --from DIR (the same design, seed and tests) writing DIR/power.json.
studies::SlurmSeries power_series(const Arguments& args, const power::PowerOptions& options) {
  studies::SlurmSeries series = series_settings(args);
  for (const auto& per_n : studies::pipeline_studies(options))
    for (const studies::PipelineStudy& s : per_n)
      series.studies.push_back({s.participants, s.seed});
  series.simulate_options = {"--world", args.text("world")};
  series.then = {series.cli,
                 "power",
                 "--protocol",
                 series.protocol,
                 "--pipeline",
                 "--world",
                 args.text("world"),
                 "--n",
                 args.text("n"),
                 "--sims",
                 std::to_string(options.sims),
                 "--alpha",
                 args.text("alpha"),
                 "--target",
                 args.text("target"),
                 "--seed",
                 args.text("seed"),
                 "--correction",
                 args.text("correction"),
                 "--from",
                 series.dir,
                 "--quiet",
                 "--json",
                 series.dir + "/power.json"};
  if (args.has("plot")) {
    series.then.push_back("--plot");
    series.then.push_back(std::filesystem::absolute(args.text("plot")).string());
  }
  for (const std::string& name : args.all("plot-name")) {
    series.then.push_back("--plot-name");
    series.then.push_back(name);
  }
  return series;
}

}  // namespace

namespace {

std::vector<OptionSpec> power_options() {
  std::vector<OptionSpec> specs = {
      {"protocol", "FILE", "the study protocol (its factors and blocks make the design)"},
      {"model", "FILE", "the data's model: cell means, SDs, correlation, ... (docs/power.md)"},
      {"pilot", "DB", "estimate the model from a pilot study's database instead"},
      {"n", "LIST", "participants: FROM:TO:STEP (10:40:2), a list (12,20,30) or one N", "10:40:2"},
      {"sims", "S", "simulated studies per N", "1000"},
      {"alpha", "A", "the significance level", "0.05"},
      {"target", "P", "the power whose smallest N is reported", "0.8"},
      {"seed", "S", "the simulations' seed: the same seed gives the same powers", "1"},
      {"jobs", "J", "threads (results do not depend on it; default: the machine's cores)", "0"},
      {"correction", "auto|none|gg|hf",
       "the p of effects with more than one df: auto = Greenhouse-Geisser where Mauchly's test "
       "rejects sphericity, as the study report decides",
       "auto"},
      {"pipeline", "",
       "answer with whole simulated studies (simulated participants, retargeting, physics, "
       "task, study database) instead of a model; slow: use a small --sims (default 5)"},
      world_option(),
      {"exact", "",
       "the ANOVA effects and contrasts from the noncentral F and t of data with "
       "exactly the model's moments, instead of simulating"},
      {"plot", "FILE", "draw the power curves (.svg or .png)"},
      {"plot-name", "NAME",
       "an effect or contrast to draw (repeatable; default: the protocol's "
       "factors' effects)",
       "", true},
      {"slurm", "DIR",
       "with --pipeline: instead of running here, write the studies as Slurm batch jobs into "
       "DIR and submit them (a job array, a merge job, then this analysis into DIR/power.json; "
       "docs/cluster.md)"},
      {"from", "DIR",
       "with --pipeline: analyse the studies the Slurm series in DIR merged instead of "
       "simulating them"},
      {"quiet", "", "no progress line"},
      {"json", "OUT", "write the results as JSON (- for standard output)"},
  };
  for (const OptionSpec& spec : slurm_option_specs()) specs.push_back(spec);
  return specs;
}

CommandHelp power_help() {
  return {"power",
          {"protocol (pilot|model) [n] [sims] [alpha] [target] [seed] [correction] [exact] [plot] "
           "[json] [options]",
           "protocol pipeline [world] [n] [sims] [alpha] [target] [seed] [correction] [plot] "
           "[json] [options]",
           "protocol pipeline slurm [per-task] [dry-run] [options]"},
          "For every N, simulates studies of the protocol's design from the model (or, with "
          "--pipeline, runs whole simulated studies) and analyses each as `analyze --db` does "
          "(RM-ANOVA with the sphericity correction, Tukey-adjusted pairwise comparisons, "
          "Friedman and Bonferroni-adjusted Wilcoxon tests per questionnaire item): the power of "
          "every effect and planned contrast with its Monte Carlo SE and 95 % interval, and the "
          "smallest N reaching the target. With --pipeline --slurm, the studies run as Slurm "
          "jobs and the power is written to DIR/power.json when they are merged "
          "(docs/cluster.md)."};
}

}  // namespace

namespace {

// The modes' refusals: --pipeline or one of --model and --pilot, Slurm with --pipeline.
void check_modes(const Arguments& args) {
  const bool pipeline = args.flag("pipeline");
  if (pipeline && (args.has("model") || args.has("pilot") || args.flag("exact")))
    throw UsageError("--pipeline simulates participants: it takes no --model, --pilot or --exact");
  for (const char* option : {"slurm", "from"})
    if (args.has(option) && !pipeline)
      throw UsageError(std::string("--") + option + " goes with --pipeline");
  if (!args.has("slurm") && has_slurm_options(args))
    throw UsageError("--per-task, --partition, --time, --mem and --dry-run go with --slurm");
  if (!pipeline && args.has("model") == args.has("pilot"))
    throw UsageError("give one of --model FILE or --pilot DB (or --pipeline)");
}

power::PowerOptions simulation_options(const Arguments& args) {
  power::PowerOptions options;
  options.n = parse_n(args.text("n"));
  options.sims = args.flag("pipeline") && !args.has("sims") ? 5 : int(args.integer("sims"));
  if (options.sims < 1) throw UsageError("--sims must be 1 or more");
  options.alpha = args.number("alpha");
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be in (0, 1)");
  options.seed = args.seed("seed");
  options.threads = int(args.integer("jobs"));
  if (options.threads < 0) throw UsageError("--jobs must be 0 (all cores) or more");
  if (options.threads == 0)
    options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  options.correction = sphericity_correction(args.text("correction"));
  return options;
}

// The power of every N: exact, from whole simulated studies, or simulated from the model.
power::PowerReport compute_power(const Arguments& args, const studies::Protocol& protocol,
                                 const power::PowerModel& model, const power::PowerOptions& options,
                                 bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const bool exact = args.flag("exact");
  ProgressLine progress(quiet || exact);
  power::PowerReport report;
  if (exact) {
    report = power::exact_power(model, options);
  } else if (args.flag("pipeline")) {
    studies::PipelinePowerOptions po;
    po.power = options;
    if (args.has("from")) po.from_dir = args.text("from");
    po.world = world_kind(args);
    report = studies::pipeline_power(protocol, po, [&](int done, int total) {
      char text[120];
      std::snprintf(text, sizeof text, "simulated studies %d/%d  %.0f s", done, total, elapsed());
      progress.show(done, text);
    });
  } else {
    report = power::simulate_power(model, options, [&](int done, int total) {
      char text[120];
      std::snprintf(text, sizeof text, "N %d/%d  %d simulations  %.1f s", done, total,
                    done * options.sims, elapsed());
      progress.show(done, text);
    });
  }
  progress.finish();
  return report;
}

void print_power(const Arguments& args, const power::PowerReport& report,
                 const power::PowerOptions& options, double target, double seconds) {
  const bool exact = args.flag("exact");
  if (args.has("pilot"))
    std::cout << "Note: these powers are for the pilot's own observed effects (observed power), "
                 "which says nothing the pilot's p values do not; the power of the design is "
                 "for the effect you want to detect: write it in a --model file.\n\n";
  for (const std::string& note : report.notes) std::cout << "Note: " << note << "\n";
  std::cout << (exact ? std::string("Exact power (noncentral F and t of the model's moments)")
                : args.flag("pipeline")
                    ? std::to_string(options.sims) + " whole simulated studies per N on the " +
                          (args.text("world") == "soft" ? "soft hand" : "grasp proxy")
                    : std::to_string(options.sims) + " simulated studies per N")
            << ", alpha = " << options.alpha << ", " << std::fixed << std::setprecision(2)
            << seconds << " s\n\n"
            << std::defaultfloat;
  print_table(report, report.effects, "effect", target);
  std::cout << "\n";
  print_table(report, report.contrasts, "contrast", target);
  int warned = 0;
  for (int w : report.warnings) warned += w;
  if (warned) {
    std::cout << "\n" << warned << " simulation(s) with warnings, e.g.:\n";
    for (const std::string& e : report.warning_examples) std::cout << "  " << e << "\n";
  }
}

void write_power_json(std::ostream& out, const Arguments& args, const power::PowerReport& report,
                      const power::PowerOptions& options, double target, double seconds) {
  const bool exact = args.flag("exact");
  util::JsonWriter w(out);
  w.begin_object();
  w.key("n").begin_array();
  for (int n : report.n) w.value(n);
  w.end_array();
  const auto effects = pointers(report.effects), contrasts = pointers(report.contrasts);
  std::vector<const power::PowerEstimate*> all = effects;
  all.insert(all.end(), contrasts.begin(), contrasts.end());
  write_map(w, "effects", effects, &power::PowerEstimate::power);
  write_map(w, "contrasts", contrasts, &power::PowerEstimate::power);
  write_map(w, "mc_se", all, &power::PowerEstimate::mc_se);
  write_map(w, "lower", all, &power::PowerEstimate::lower);
  write_map(w, "upper", all, &power::PowerEstimate::upper);
  w.key("n_for_target").begin_object();
  for (const power::PowerEstimate* e : all) {
    w.key(e->name);
    if (const auto n = power::n_for_target(report, *e, target))
      w.value(*n);
    else
      w.null();
  }
  w.end_object();
  w.field("target", target).field("alpha", options.alpha).field("exact", exact);
  w.field("pipeline", args.flag("pipeline"));
  w.field("sims", exact ? 0 : options.sims).field("seed", options.seed);
  w.field("seconds", seconds);
  w.key("seconds_per_n").begin_array();
  for (double s : report.seconds) w.value(s);
  w.end_array();
  w.key("warnings").begin_array();
  for (int v : report.warnings) w.value(v);
  w.end_array();
  w.key("notes").begin_array();
  for (const std::string& n : report.notes) w.value(n);
  w.end_array();
  w.field("observed_power", args.has("pilot"));
  w.end_object();
  out << "\n";
}

#ifdef HANDLAB_WITH_REPORT
// --plot: the powers of the named effects (by default the main effects and interactions).
void draw_power(const Arguments& args, const power::PowerReport& report,
                const studies::Protocol& protocol, double target) {
  std::vector<std::string> names = args.all("plot-name");
  if (names.empty())
    for (const power::PowerEstimate& e : report.effects)
      if (e.name.find("repetition") == std::string::npos && e.name.find(" (") == std::string::npos)
        names.push_back(e.name);
  ensure_gui_application();
  report::write_power_figure(report, names, target,
                             "Power of " + protocol.name + (args.flag("exact") ? " (exact)" : ""),
                             args.text("plot"));
}
#endif

}  // namespace

int run_power(const std::vector<std::string>& argv) {
  const Arguments args(power_options(), argv);
  if (args.help_requested()) return print_help(power_help(), args);
  args.require({"protocol"});
  check_modes(args);
  args.choice("world", {"proxy", "soft"});
  const studies::Protocol protocol = studies::read_protocol(args.text("protocol"));
  const power::PowerDesign design = studies::power_design(protocol);
  power::PowerModel model;
  if (args.has("model")) model = power::read_power_model(args.text("model"), design);
  if (args.has("pilot")) model = studies::estimate_from_pilot(args.text("pilot"), protocol);
  const power::PowerOptions options = simulation_options(args);
  const double target = args.number("target");
  if (!(target > 0 && target < 1)) throw UsageError("--target must be in (0, 1)");
  // An output on standard output is all that is printed there.
  const bool to_stdout = args.text("json") == "-" || args.text("plot") == "-";
  if (args.has("slurm")) {
    submit_slurm_series(power_series(args, options), args.flag("dry-run"));
    return 0;
  }
#ifndef HANDLAB_WITH_REPORT
  if (args.has("plot")) throw UsageError("--plot needs handlab-cli built with Qt (the app)");
#endif
  const auto start = std::chrono::steady_clock::now();
  power::PowerReport report =
      compute_power(args, protocol, model, options, args.flag("quiet") || to_stdout);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!protocol.between.empty() && !args.flag("pipeline"))  // the model is of the within cells
    report.notes.insert(report.notes.begin(),
                        "the protocol's between-participants factors are not in the power "
                        "model: its groups are pooled, and the powers are of the within "
                        "effects");
  if (!to_stdout) print_power(args, report, options, target, seconds);
#ifdef HANDLAB_WITH_REPORT
  if (args.has("plot")) draw_power(args, report, protocol, target);
#endif
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& out) {
      write_power_json(out, args, report, options, target, seconds);
    });
  return 0;
}

}  // namespace handlab::cli
