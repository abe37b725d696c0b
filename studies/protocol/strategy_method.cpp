#include "studies/protocol/strategy_method.h"

#include <algorithm>
#include <iterator>

#include "core/util/csv.h"

namespace handlab::studies {
namespace {

using util::JsonValue;

constexpr const char* kOursParameters[] = {"tip_weights",           "spatial_weight",
                                           "temporal_weight",       "max_iterations",
                                           "cold_start_iterations", "trust_radius"};

std::string listed(const char* const* first, const char* const* last) {
  std::string out;
  for (; first != last; ++first) out += std::string(out.empty() ? "" : ", ") + *first;
  return out;
}

retarget::OursOptions read_ours_parameters(const ProtocolReader& r, const JsonValue& parameters,
                                           const std::string& where) {
  if (!parameters.is_object()) r.fail(where, "must be an object");
  for (const auto& [key, value] : parameters.as_object())
    if (std::none_of(std::begin(kOursParameters), std::end(kOursParameters),
                     [&](const char* k) { return key == k; }))
      r.fail(where, "method \"ours\" takes no parameter \"" + key + "\" (it takes " +
                        listed(std::begin(kOursParameters), std::end(kOursParameters)) + ")");
  retarget::OursOptions ours;
  retarget::SolverOptions& s = ours.solver;
  if (const JsonValue* w = parameters.find("tip_weights")) {
    if (!w->is_array() || w->size() != 5)
      r.fail(where + ".tip_weights", "must list five weights, thumb to little finger");
    double sum = 0;
    for (std::size_t f = 0; f < 5; ++f) {
      const JsonValue& x = (*w)[f];
      if (!x.is_number() || !(x.as_number() >= 0 && x.as_number() <= 1000))
        r.fail(where + ".tip_weights", "each weight is a number in [0, 1000]");
      ours.tip_weights[f] = x.as_number();
      sum += x.as_number();
    }
    if (sum <= 0) r.fail(where + ".tip_weights", "at least one fingertip must count");
  }
  // Above zero: the regularisers keep the fit's matrix positive definite (a finger has more
  // joints than its tip pins down).
  s.spatial_weight = r.number(parameters, "spatial_weight", where, 1e-12, 1e-3, s.spatial_weight);
  s.temporal_weight =
      r.number(parameters, "temporal_weight", where, 1e-12, 1e-3, s.temporal_weight);
  s.max_iterations = r.integer(parameters, "max_iterations", where, 1, 1000, s.max_iterations);
  s.cold_start_iterations =
      r.integer(parameters, "cold_start_iterations", where, 1, 10000, s.cold_start_iterations);
  s.trust_radius = r.number(parameters, "trust_radius", where, 0.01, 3.2, s.trust_radius);
  return ours;
}

}  // namespace

StrategyMethod read_strategy_method(const ProtocolReader& r, const JsonValue& level,
                                    const std::string& where) {
  const std::string name = r.text(level, "name", where);
  const JsonValue* given = level.find("method");
  if (!given && name != "naive" && name != "ours")
    r.fail(where, "\"method\" is required (\"naive\" or \"ours\"): the name \"" + name +
                      "\" is a label only");
  const std::string method = given ? r.text(level, "method", where) : name;
  StrategyMethod out;
  if (method == "naive")
    out.method = retarget::Strategy::kNaive;
  else if (method != "ours")
    r.fail(where + ".method", "unknown method \"" + method + "\" (known: naive, ours)");
  if (const JsonValue* parameters = level.find("parameters")) {
    if (out.method == retarget::Strategy::kNaive)
      r.fail(where + ".parameters", "method \"naive\" takes no parameters");
    out.ours = read_ours_parameters(r, *parameters, where + ".parameters");
  }
  return out;
}

std::string describe(const StrategyMethod& m) {
  if (m.method == retarget::Strategy::kNaive) return "naive";
  const retarget::OursOptions defaults;
  const retarget::SolverOptions &s = m.ours.solver, &d = defaults.solver;
  std::string changed;
  auto add = [&](const std::string& what) { changed += (changed.empty() ? "" : "; ") + what; };
  if (m.ours.tip_weights != defaults.tip_weights) {
    std::string weights;
    for (double w : m.ours.tip_weights)
      weights += (weights.empty() ? "" : ", ") + util::format_number(w);
    add("tip weights " + weights);
  }
  if (s.spatial_weight != d.spatial_weight)
    add("spatial weight " + util::format_number(s.spatial_weight));
  if (s.temporal_weight != d.temporal_weight)
    add("temporal weight " + util::format_number(s.temporal_weight));
  if (s.max_iterations != d.max_iterations)
    add("max iterations " + std::to_string(s.max_iterations));
  if (s.cold_start_iterations != d.cold_start_iterations)
    add("cold-start iterations " + std::to_string(s.cold_start_iterations));
  if (s.trust_radius != d.trust_radius) add("trust radius " + util::format_number(s.trust_radius));
  return changed.empty() ? "ours" : "ours (" + changed + ")";
}

}  // namespace handlab::studies
