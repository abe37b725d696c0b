#include "studies/sensitivity/model_sensitivity.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numeric>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "core/store/sqlite_database.h"
#include "core/util/json_value.h"
#include "core/util/json_writer.h"
#include "studies/analysis/study_database_analysis.h"
#include "studies/analysis/study_tests.h"
#include "studies/participant/participant_model.h"
#include "studies/simulate/simulated_study.h"

namespace handlab::studies {
namespace {

constexpr const char* kPerson = "a person's parameter: the population mean within one SD";
constexpr const char* kSourced = "a fixed parameter with a source: within 25 %";
constexpr const char* kAssumed = "an assumption: half to twice its value";

}  // namespace

const std::vector<SensitivityParameter>& participant_sensitivity_parameters() {
  static const std::vector<SensitivityParameter> list = [] {
    std::vector<SensitivityParameter> p;
    for (const ParameterDistribution& d : frozen_participant_model().distributions)
      if (d.sd > 0) p.push_back({d.name, d.mean - d.sd, d.mean + d.sd, kPerson});
    const std::vector<std::pair<std::string, double>> values =
        model_parameters(frozen_participant_model());
    auto value = [&](const std::string& name) {
      for (const auto& [n, v] : values)
        if (n == name) return v;
      throw std::logic_error("no model parameter " + name);
    };
    for (const char* name : {"reaction_tau", "noise_constant", "noise_proportional",
                             "aperture_slope", "peak_aperture_at", "confirm_dwell"})
      p.push_back({name, 0.75 * value(name), 1.25 * value(name), kSourced});
    for (const char* name :
         {"regrasp_squeeze", "regrasp_lower", "post_error_caution", "approach_height",
          "pre_contact_margin", "closing_past_contact", "grip_loading", "servo_gain",
          "reach_tolerance_share", "slow_closing", "placement_margin"})
      p.push_back({name, 0.5 * value(name), 2.0 * value(name), kAssumed});
    // A share of a duration, or of what a memory keeps, cannot pass 1.
    p.push_back({"practice_floor", 0.4, 0.8, "an assumption: 0.4 to 0.8"});
    p.push_back({"grip_retention", 0.7, 0.99, "an assumption: 0.7 to 0.99"});
    return p;
  }();
  return list;
}

std::vector<std::string> default_sensitivity_outputs(const Protocol& protocol) {
  std::string interaction;
  for (const Factor& f : protocol.factors) interaction += (interaction.empty() ? "" : ":") + f.name;
  std::vector<std::string> outputs = {interaction, "repetition"};
  if (protocol.factors.size() >= 2) {
    const std::vector<Level>& first = protocol.factors[0].levels;
    std::string rest;  // the other factors at their last level
    for (std::size_t f = 1; f < protocol.factors.size(); ++f)
      rest += " " + protocol.factors[f].levels.back().name;
    outputs.push_back(interaction + ": " + first[0].name + rest + " - " + first[1].name + rest);
  }
  return outputs;
}

SensitivityReport run_model_sensitivity(
    const Protocol& protocol, const SensitivityOptions& options,
    const std::function<void(const SensitivityProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  SensitivityReport report;
  for (const SensitivityParameter& p : participant_sensitivity_parameters())
    if (options.only.empty() ||
        std::find(options.only.begin(), options.only.end(), p.name) != options.only.end())
      report.parameters.push_back(p);
  for (const std::string& name : options.only)
    if (std::none_of(report.parameters.begin(), report.parameters.end(),
                     [&](const SensitivityParameter& p) { return p.name == name; }))
      throw std::invalid_argument("the sensitivity analysis has no parameter " + name);
  report.outputs =
      options.outputs.empty() ? default_sensitivity_outputs(protocol) : options.outputs;
  report.design = morris_design(int(report.parameters.size()), options.trajectories, options.levels,
                                options.design_seed);
  std::filesystem::create_directories(options.work_dir);
  const int points = int(report.design.points.size());
  for (int k = 0; k < points; ++k) {
    std::vector<std::pair<std::string, double>> changes;
    for (std::size_t i = 0; i < report.parameters.size(); ++i) {
      const SensitivityParameter& p = report.parameters[i];
      changes.emplace_back(p.name,
                           p.low + report.design.points[std::size_t(k)][i] * (p.high - p.low));
    }
    SimulationOptions run;
    run.participants = options.participants;
    run.seed = options.seed;
    run.jobs = options.jobs;
    run.world = options.world;
    run.model = changed_model(frozen_participant_model(), changes);
    const std::string db =
        (std::filesystem::path(options.work_dir) / ("point-" + std::to_string(k + 1) + ".db"))
            .string();
    store::remove_database_files(db);
    StudyTests tests;
    try {
      simulate_study(protocol, db, run);
      tests = study_tests(analyze_study_database(db), power::SphericityCorrection::kAuto, 0.05);
    } catch (...) {
      store::remove_database_files(db);  // the parts a failed simulation left are removed with it
      for (const auto& f : std::filesystem::directory_iterator(options.work_dir))
        if (f.path().filename().string().rfind(
                std::filesystem::path(db).filename().string() + ".part-", 0) == 0)
          std::filesystem::remove(f.path());
      throw;
    }
    store::remove_database_files(db);
    std::vector<double> values;
    for (const std::string& name : report.outputs) {
      double v = std::numeric_limits<double>::quiet_NaN();
      for (const StudyTest& t : tests.tests)
        if (t.name == name) v = t.value;
      values.push_back(v);
    }
    report.values.push_back(values);
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress({k + 1, points, report.seconds});
  }
  for (std::size_t o = 0; o < report.outputs.size(); ++o) {
    std::vector<double> output;
    for (const auto& v : report.values) output.push_back(v[o]);
    report.indices.push_back(morris_indices(report.design, output));
  }
  return report;
}

void write_sensitivity_markdown(const SensitivityReport& r, std::ostream& out) {
  out << "Morris elementary effects: " << r.design.points.size() << " studies ("
      << r.design.points.size() / (r.parameters.size() + 1) << " trajectories of "
      << r.parameters.size() << " parameters, " << r.design.levels << " levels) in " << std::fixed
      << std::setprecision(0) << r.seconds << " s\n";
  for (std::size_t o = 0; o < r.outputs.size(); ++o) {
    out << "\n"
        << r.outputs[o] << ": each parameter's effect over its range, largest first\n\n"
        << "| parameter | range | mu* | mu | sigma | basis |\n|---|---|---|---|---|---|\n";
    std::vector<std::size_t> order(r.parameters.size());
    std::iota(order.begin(), order.end(), 0);
    const auto& m = r.indices[o];
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return (std::isnan(m[b].mu_star) ? -1.0 : m[b].mu_star) <
             (std::isnan(m[a].mu_star) ? -1.0 : m[a].mu_star);
    });
    for (std::size_t i : order) {
      const SensitivityParameter& p = r.parameters[i];
      out << "| " << p.name << " | " << std::setprecision(4) << std::defaultfloat << p.low << "–"
          << p.high << " | " << std::fixed << std::setprecision(2) << m[i].mu_star << " | "
          << m[i].mu << " | " << m[i].sigma << " | " << p.basis << " |\n";
    }
  }
}

void write_sensitivity_json(const SensitivityReport& r, std::ostream& out) {
  util::JsonWriter w(out);
  w.begin_object().field("seconds", r.seconds).field("levels", r.design.levels);
  w.field("trajectories", int(r.design.points.size() / (r.parameters.size() + 1)));
  w.key("parameters").begin_array();
  for (const SensitivityParameter& p : r.parameters)
    w.begin_object()
        .field("name", p.name)
        .field("low", p.low)
        .field("high", p.high)
        .field("basis", p.basis)
        .end_object();
  w.end_array().key("outputs").begin_array();
  for (std::size_t o = 0; o < r.outputs.size(); ++o) {
    w.begin_object().field("test", r.outputs[o]).key("indices").begin_object();
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      const MorrisIndex& m = r.indices[o][i];
      w.key(r.parameters[i].name)
          .begin_object()
          .field("mu_star", m.mu_star)
          .field("mu", m.mu)
          .field("sigma", m.sigma)
          .field("effects", m.effects)
          .end_object();
    }
    w.end_object().end_object();
  }
  w.end_array().key("points").begin_array();
  for (std::size_t k = 0; k < r.design.points.size(); ++k) {
    w.begin_object().key("unit").begin_array();
    for (double x : r.design.points[k]) w.value(x);
    w.end_array().key("values").begin_array();
    for (double v : r.values[k]) w.value(v);
    w.end_array().end_object();
  }
  w.end_array().end_object();
  out << "\n";
}

SensitivityReport read_sensitivity_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    const util::JsonValue v = util::JsonValue::parse(text.str());
    const auto number = [](const util::JsonValue& x) {
      return x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.as_number();
    };
    SensitivityReport r;
    r.seconds = v["seconds"].as_number();
    r.design.levels = int(v["levels"].as_number());
    for (const util::JsonValue& p : v["parameters"].as_array())
      r.parameters.push_back({p["name"].as_string(), p["low"].as_number(), p["high"].as_number(),
                              p["basis"].as_string()});
    r.design.parameters = int(r.parameters.size());
    for (const util::JsonValue& o : v["outputs"].as_array()) {
      r.outputs.push_back(o["test"].as_string());
      std::vector<MorrisIndex>& indices = r.indices.emplace_back();
      for (const SensitivityParameter& p : r.parameters) {
        const util::JsonValue& i = o["indices"][p.name];
        indices.push_back({number(i["mu"]), number(i["mu_star"]), number(i["sigma"]),
                           int(i["effects"].as_number())});
      }
    }
    for (const util::JsonValue& point : v["points"].as_array()) {
      std::vector<double>& unit = r.design.points.emplace_back();
      for (const util::JsonValue& x : point["unit"].as_array()) unit.push_back(x.as_number());
      std::vector<double>& values = r.values.emplace_back();
      for (const util::JsonValue& x : point["values"].as_array()) values.push_back(number(x));
    }
    return r;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + " is not a sensitivity analysis: " + e.what());
  }
}

}  // namespace handlab::studies
