// A generative model of a repeated-measures study's data, for simulation-based power
// analysis (docs/power.md): per within cell (the protocol's conditions x repetition) a mean
// and an SD, a correlation between cells (one value or the full matrix), a probability that a
// trial has no result, covariates with per-cell slopes, and questionnaire items answered once
// per condition on a Likert scale. Given in a small JSON file or estimated from a pilot.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/stats/rm_data.h"

namespace handlab::power {

// The study's within design: its factors (in the protocol's order) and the repetitions of
// each condition, which form one more within factor, "repetition" (levels "1".."R"), as
// `analyze --db` analyses it. Cells are numbered with the first factor varying fastest.
struct PowerDesign {
  std::vector<stats::Factor> factors;
  int repetitions = 1;

  std::vector<stats::Factor> within() const;  // the factors, then repetition when R > 1
  int conditions() const;                     // cells of the factors alone
  int cells() const { return conditions() * repetitions; }
  int condition_of_cell(int cell) const { return cell % conditions(); }
  // "naive-gross": the levels of a condition joined by '-', as a protocol labels it.
  std::string condition_label(int condition) const;
  int condition_index(const std::string& label) const;  // -1 when not a condition
};

struct PowerCovariate {
  std::string name;
  double mean = 0.0, sd = 0.0;
  Eigen::VectorXd slope;  // per cell: dv units per covariate unit
};

struct PowerItem {
  std::string name;
  int scale_points = 5;
  Eigen::VectorXd mean;      // per condition, on the latent scale (1..scale_points)
  double sd = 1.0;           // latent SD
  double correlation = 0.0;  // between conditions, within a participant
};

struct PowerModel {
  PowerDesign design;
  std::string dv = "completion_time_s";
  Eigen::VectorXd mean, sd;     // per cell
  Eigen::MatrixXd correlation;  // cells x cells
  double missing = 0.0;         // probability that a trial has no result
  std::vector<PowerCovariate> covariates;
  std::vector<PowerItem> items;
  // Post hoc effects whose pairwise comparisons are the planned contrasts ("a:b"); by default
  // the protocol's factors together.
  std::vector<std::string> contrast_effects;
  std::vector<std::string> notes;  // how it was made (estimation choices)

  Eigen::MatrixXd covariance() const;  // of a participant's cells
};

// One correlation r between every two of n cells (ones on the diagonal).
Eigen::MatrixXd exchangeable_correlation(int n, double r);

// Reads a model file (format "handlab-power-model", docs/power.md) for `design`, validating
// every condition label, length and value; throws std::runtime_error naming what is wrong.
PowerModel read_power_model(const std::string& path, const PowerDesign& design);
PowerModel parse_power_model(const std::string& json_text, const PowerDesign& design,
                             const std::string& source = "model");

// Estimates the model from a pilot's data (participants x cells of `design`, as
// prepare_rm_data arranges them): cell means and SDs, and the sample correlation matrix when
// the pilot has more participants than cells and it is positive definite, otherwise one
// correlation (the mean of the off-diagonal ones), said in `notes`. `missing` is the share
// of planned results the pilot lacks. `items` (participants x conditions per item) give the
// items' means, pooled SD and mean correlation.
struct PilotItem {
  std::string name;
  int scale_points = 5;
  Eigen::MatrixXd answers;  // participants x conditions
};
PowerModel estimate_power_model(const PowerDesign& design, const Eigen::MatrixXd& cells,
                                double missing = 0.0, const std::vector<PilotItem>& items = {});

}  // namespace handlab::power
