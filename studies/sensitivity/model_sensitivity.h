// The participant model's global sensitivity analysis: a Morris design (morris.h) over the
// model's parameters, each within a stated range, a whole simulated study at every point (the
// same population seed throughout, so that points differ by their parameters alone), and per
// output test (an ANOVA effect's F, a contrast's t, as study_tests names them) each
// parameter's mu* and sigma in the output's units over the parameter's range.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "studies/protocol/protocol.h"
#include "studies/sensitivity/morris.h"
#include "studies/session/trial_driver.h"

namespace handlab::studies {

struct SensitivityParameter {
  std::string name;  // as changed_model names it
  double low = 0.0, high = 0.0;
  std::string basis;  // why this range
};

// The parameters and their ranges: a per-person parameter's population mean within one
// between-person SD; a fixed parameter with a source within 25 %; an assumption from half to
// twice its value (or its stated bounds).
const std::vector<SensitivityParameter>& participant_sensitivity_parameters();

struct SensitivityOptions {
  int participants = 20;
  std::uint64_t seed = 1;  // the population's
  int trajectories = 4, levels = 4;
  std::uint64_t design_seed = 1;
  int jobs = 2;
  WorldKind world = WorldKind::kGraspProxy;
  std::string work_dir;              // where each point's study database is written (and removed)
  std::vector<std::string> outputs;  // tests as replications names them; empty: the defaults
  // Only these of participant_sensitivity_parameters() (by name); empty: all of them.
  std::vector<std::string> only;
};

struct SensitivityReport {
  std::vector<SensitivityParameter> parameters;
  std::vector<std::string> outputs;
  MorrisDesign design;
  std::vector<std::vector<double>> values;  // per point, per output (NaN: the study lacks it)
  // Per output, per parameter, in the output's units over the parameter's whole range.
  std::vector<std::vector<MorrisIndex>> indices;
  double seconds = 0.0;
};

struct SensitivityProgress {
  int points_done = 0, points = 0;
  double seconds = 0.0;
};

// The protocol's within factors' interaction F (or its one factor's F), the repetition F
// and, with two factors or more, the t of the first factor's first two levels at every other
// factor's last level, labelled as the protocol labels them. The study's:
// "strategy:manipulation", "repetition", "strategy:manipulation: naive fine - ours fine".
std::vector<std::string> default_sensitivity_outputs(const Protocol& protocol);

// Throws std::invalid_argument when `only` names a parameter the analysis lacks.
SensitivityReport run_model_sensitivity(
    const Protocol& protocol, const SensitivityOptions& options,
    const std::function<void(const SensitivityProgress&)>& progress = {});

// Per output, the parameters by mu* (largest first): mu*, mu, sigma.
void write_sensitivity_markdown(const SensitivityReport& report, std::ostream& out);
void write_sensitivity_json(const SensitivityReport& report, std::ostream& out);
// The report write_sensitivity_json wrote to the file `path` (the design's points, not its
// steps: what the tables and the figure need). Throws std::runtime_error naming the file
// when it cannot be read or is not such a report.
SensitivityReport read_sensitivity_json(const std::string& path);

}  // namespace handlab::studies
