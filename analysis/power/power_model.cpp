#include "analysis/power/power_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "core/util/data_files.h"
#include "core/util/json_value.h"

namespace handlab::power {
namespace {

using util::JsonValue;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw std::runtime_error(source + ": " + what);
}

// A value given once for every condition or per condition label: {"naive-gross": 1, ...}.
Eigen::VectorXd per_condition(const JsonValue& v, const PowerDesign& d, const std::string& key,
                              const std::string& source, bool all_required) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(d.conditions());
  if (v.is_number()) return out.setConstant(v.as_number());
  if (!v.is_object()) fail(source, "'" + key + "' must be a number or an object of conditions");
  std::vector<bool> seen(std::size_t(d.conditions()), false);
  for (const auto& [label, value] : v.as_object()) {
    const int c = d.condition_index(label);
    if (c < 0) fail(source, "'" + key + "' names '" + label + "', which is not a condition");
    if (!value.is_number() || !std::isfinite(value.as_number()))
      fail(source, "'" + key + "." + label + "' must be a number");
    out[c] = value.as_number();
    seen[std::size_t(c)] = true;
  }
  if (all_required)
    for (int c = 0; c < d.conditions(); ++c)
      if (!seen[std::size_t(c)])
        fail(source, "'" + key + "' lacks condition '" + d.condition_label(c) + "'");
  return out;
}

// Per repetition, added to every condition or per condition label.
Eigen::MatrixXd repetition_effect(const JsonValue* v, const PowerDesign& d,
                                  const std::string& source) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(d.conditions(), d.repetitions);
  if (!v) return out;
  auto row = [&](const JsonValue& a, const std::string& what) {
    if (!a.is_array() || int(a.size()) != d.repetitions)
      fail(source, what + " must list " + std::to_string(d.repetitions) + " numbers");
    Eigen::RowVectorXd r(d.repetitions);
    for (int k = 0; k < d.repetitions; ++k) r[k] = a[std::size_t(k)].as_number();
    return r;
  };
  if (v->is_array()) {
    out.rowwise() = row(*v, "'repetition_effect'");
    return out;
  }
  if (!v->is_object()) fail(source, "'repetition_effect' must be an array or an object");
  for (const auto& [label, value] : v->as_object()) {
    const int c = d.condition_index(label);
    if (c < 0) fail(source, "'repetition_effect' names '" + label + "', which is not a condition");
    out.row(c) = row(value, "'repetition_effect." + label + "'");
  }
  return out;
}

double number(const JsonValue& o, const char* key, double fallback, const std::string& source) {
  const JsonValue* v = o.find(key);
  if (!v) return fallback;
  if (!v->is_number() || !std::isfinite(v->as_number()))
    fail(source, std::string("'") + key + "' must be a number");
  return v->as_number();
}

bool positive_definite(const Eigen::MatrixXd& m) {
  Eigen::LLT<Eigen::MatrixXd> llt(m);
  return llt.info() == Eigen::Success;
}

}  // namespace

Eigen::MatrixXd exchangeable_correlation(int n, double r) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Constant(n, n, r);
  m.diagonal().setOnes();
  return m;
}

std::vector<stats::Factor> PowerDesign::within() const {
  std::vector<stats::Factor> w = factors;
  if (repetitions > 1) {
    stats::Factor r{"repetition", {}};
    for (int k = 1; k <= repetitions; ++k) r.levels.push_back(std::to_string(k));
    w.push_back(r);
  }
  return w;
}

int PowerDesign::conditions() const {
  int n = 1;
  for (const stats::Factor& f : factors) n *= int(f.levels.size());
  return n;
}

std::string PowerDesign::condition_label(int condition) const {
  std::string label;
  for (const stats::Factor& f : factors) {
    const int k = int(f.levels.size());
    label += (label.empty() ? "" : "-") + f.levels[std::size_t(condition % k)];
    condition /= k;
  }
  return label;
}

int PowerDesign::condition_index(const std::string& label) const {
  for (int c = 0; c < conditions(); ++c)
    if (condition_label(c) == label) return c;
  return -1;
}

Eigen::MatrixXd PowerModel::covariance() const {
  return sd.asDiagonal() * correlation * sd.asDiagonal();
}

PowerModel parse_power_model(const std::string& text, const PowerDesign& design,
                             const std::string& source) {
  JsonValue doc;
  try {
    doc = JsonValue::parse(text);
  } catch (const util::JsonError& e) {
    fail(source, e.what());
  }
  if (!doc.is_object()) fail(source, "a model is a JSON object");
  if (const JsonValue* f = doc.find("format");
      f && (!f->is_string() || f->as_string() != "handlab-power-model"))
    fail(source, "'format' must be \"handlab-power-model\"");
  PowerModel m;
  m.design = design;
  const int conditions = design.conditions(), cells = design.cells();
  if (const JsonValue* dv = doc.find("dv")) m.dv = dv->as_string();
  const JsonValue* means = doc.find("means");
  if (!means) fail(source, "'means' (per condition) is required");
  const Eigen::VectorXd condition_mean = per_condition(*means, design, "means", source, true);
  const Eigen::MatrixXd repetition =
      repetition_effect(doc.find("repetition_effect"), design, source);
  const JsonValue* sd = doc.find("sd");
  if (!sd) fail(source, "'sd' is required");
  const Eigen::VectorXd condition_sd = per_condition(*sd, design, "sd", source, true);
  if ((condition_sd.array() <= 0).any()) fail(source, "every 'sd' must be positive");
  m.mean.resize(cells);
  m.sd.resize(cells);
  for (int c = 0; c < cells; ++c) {
    const int k = design.condition_of_cell(c), r = c / conditions;
    m.mean[c] = condition_mean[k] + repetition(k, r);
    m.sd[c] = condition_sd[k];
  }
  const JsonValue* corr = doc.find("correlation");
  if (!corr || corr->is_number()) {
    const double r = corr ? corr->as_number() : 0.0;
    if (!(r > -1.0 / (cells - 1) && r < 1.0))
      fail(source, "'correlation' must lie between -1/(cells - 1) and 1 (exclusive)");
    m.correlation = exchangeable_correlation(cells, r);
  } else {
    if (!corr->is_array() || int(corr->size()) != cells)
      fail(source, "'correlation' must be a number or a " + std::to_string(cells) + " x " +
                       std::to_string(cells) +
                       " matrix (cells: first factor fastest, repetition last)");
    m.correlation.resize(cells, cells);
    for (int i = 0; i < cells; ++i) {
      const JsonValue& row = (*corr)[std::size_t(i)];
      if (!row.is_array() || int(row.size()) != cells)
        fail(source, "row " + std::to_string(i + 1) + " of 'correlation' must have " +
                         std::to_string(cells) + " numbers");
      for (int j = 0; j < cells; ++j) m.correlation(i, j) = row[std::size_t(j)].as_number();
    }
    if (!m.correlation.isApprox(m.correlation.transpose(), 1e-12) ||
        (m.correlation.diagonal().array() - 1.0).abs().maxCoeff() > 1e-12)
      fail(source, "'correlation' must be symmetric with ones on the diagonal");
  }
  if (!positive_definite(m.correlation)) fail(source, "'correlation' is not positive definite");
  m.missing = number(doc, "missing", 0.0, source);
  if (m.missing < 0 || m.missing >= 1) fail(source, "'missing' must be in [0, 1)");
  if (const JsonValue* covs = doc.find("covariates")) {
    for (const JsonValue& c : covs->as_array()) {
      PowerCovariate v;
      v.name = c["name"].as_string();
      v.mean = number(c, "mean", 0.0, source);
      v.sd = number(c, "sd", 0.0, source);
      if (v.sd < 0) fail(source, "covariate '" + v.name + "': 'sd' must not be negative");
      const Eigen::VectorXd slope =
          per_condition(c["slope"], design, v.name + ".slope", source, false);
      v.slope.resize(cells);
      for (int k = 0; k < cells; ++k) v.slope[k] = slope[design.condition_of_cell(k)];
      m.covariates.push_back(v);
    }
  }
  if (const JsonValue* items = doc.find("items")) {
    for (const JsonValue& i : items->as_array()) {
      PowerItem item;
      item.name = i["name"].as_string();
      item.scale_points = int(number(i, "scale_points", 5, source));
      if (item.scale_points < 2) fail(source, "item '" + item.name + "': 'scale_points' below 2");
      item.mean = per_condition(i["means"], design, item.name + ".means", source, true);
      item.sd = number(i, "sd", 1.0, source);
      item.correlation = number(i, "correlation", 0.0, source);
      if (item.sd <= 0) fail(source, "item '" + item.name + "': 'sd' must be positive");
      if (!(item.correlation > -1.0 / std::max(conditions - 1, 1) && item.correlation < 1.0))
        fail(source, "item '" + item.name + "': 'correlation' out of range");
      m.items.push_back(item);
    }
  }
  if (const JsonValue* contrasts = doc.find("contrasts")) {
    for (const JsonValue& c : contrasts->as_array()) m.contrast_effects.push_back(c.as_string());
  } else {
    std::string all;
    for (const stats::Factor& f : design.factors) all += (all.empty() ? "" : ":") + f.name;
    m.contrast_effects.push_back(all);
  }
  return m;
}

PowerModel read_power_model(const std::string& named, const PowerDesign& design) {
  const std::string path = util::find_data_file(named);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_power_model(text.str(), design, path);
}

PowerModel estimate_power_model(const PowerDesign& design, const Eigen::MatrixXd& cells,
                                double missing, const std::vector<PilotItem>& items) {
  const int n = int(cells.rows()), k = design.cells();
  if (cells.cols() != k) throw std::invalid_argument("pilot data: one column per cell");
  if (n < 3) throw std::runtime_error("a pilot needs three participants or more with every cell");
  PowerModel m;
  m.design = design;
  m.missing = missing;
  m.mean = cells.colwise().mean().transpose();
  const Eigen::MatrixXd centred = cells.rowwise() - m.mean.transpose();
  const Eigen::MatrixXd covariance = centred.transpose() * centred / double(n - 1);
  m.sd = covariance.diagonal().cwiseSqrt();
  if ((m.sd.array() <= 0).any()) throw std::runtime_error("pilot data: a cell has no variance");
  const Eigen::MatrixXd full =
      m.sd.cwiseInverse().asDiagonal() * covariance * m.sd.cwiseInverse().asDiagonal();
  if (n > k && positive_definite(full)) {
    m.correlation = full;
    m.notes.push_back("correlation: the pilot's sample correlation matrix (" + std::to_string(n) +
                      " participants, " + std::to_string(k) + " cells)");
  } else {
    const double r = (full.sum() - full.trace()) / double(k * (k - 1));
    const double floor = -1.0 / (k - 1) + 1e-6;
    m.correlation = exchangeable_correlation(k, std::clamp(r, floor, 0.999));
    m.notes.push_back(
        "correlation: one value, the mean of the pilot's " + std::to_string(k * (k - 1) / 2) +
        " cell correlations (r = " + std::to_string(r) +
        "); the full matrix needs more participants than cells (" + std::to_string(n) +
        " <= " + std::to_string(k) + ") or was not positive definite");
  }
  for (const PilotItem& p : items) {
    PowerItem item;
    item.name = p.name;
    item.scale_points = p.scale_points;
    item.mean = p.answers.colwise().mean().transpose();
    const Eigen::MatrixXd c = p.answers.rowwise() - item.mean.transpose();
    const Eigen::MatrixXd cov =
        c.transpose() * c / double(std::max<Eigen::Index>(p.answers.rows() - 1, 1));
    item.sd = std::sqrt(std::max(cov.diagonal().mean(), 1e-6));
    double off = 0;
    int pairs = 0;
    for (int i = 0; i < cov.rows(); ++i)
      for (int j = i + 1; j < cov.cols(); ++j) {
        const double d = std::sqrt(cov(i, i) * cov(j, j));
        off += d > 0 ? cov(i, j) / d : 0.0;
        ++pairs;
      }
    const int q = int(cov.rows());
    item.correlation =
        std::clamp(pairs ? off / pairs : 0.0, -1.0 / std::max(q - 1, 1) + 1e-6, 0.999);
    m.items.push_back(item);
  }
  std::string all;
  for (const stats::Factor& f : design.factors) all += (all.empty() ? "" : ":") + f.name;
  m.contrast_effects.push_back(all);
  m.notes.push_back(
      "estimated from a pilot: the effects in it are the pilot's own observed effects");
  return m;
}

}  // namespace handlab::power
