#include "studies/sensitivity/morris.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/util/portable_random.h"

namespace handlab::studies {

MorrisDesign morris_design(int parameters, int trajectories, int levels, std::uint64_t seed) {
  if (parameters < 1) throw std::invalid_argument("a Morris design needs a parameter");
  if (trajectories < 2) throw std::invalid_argument("a Morris design needs two trajectories");
  if (levels < 2 || levels % 2 != 0)
    throw std::invalid_argument("a Morris design's levels must be even (4, 6, ...)");
  MorrisDesign d;
  d.parameters = parameters;
  d.levels = levels;
  const double grid = 1.0 / double(levels - 1);
  const double delta = double(levels) / (2.0 * double(levels - 1));
  util::PortableRandom random(util::splitmix64(seed ^ 0x4D6F72726973ull));  // "Morris"
  const auto below = [&](int n) { return int(random.below(std::uint64_t(n))); };
  for (int t = 0; t < trajectories; ++t) {
    // A base point on the grid, the steps in a random order, each by delta the one way the
    // grid allows from the level it is at (with an even number of levels, one way only).
    std::vector<double> x(static_cast<std::size_t>(parameters));
    for (double& v : x) v = grid * below(levels);
    std::vector<int> order(static_cast<std::size_t>(parameters));
    std::iota(order.begin(), order.end(), 0);
    random.shuffle(order);
    d.points.push_back(x);
    d.steps.push_back({});
    for (int i : order) {
      double& v = x[std::size_t(i)];
      const double step = v + delta <= 1.0 + 1e-12 ? delta : -delta;
      v += step;
      d.points.push_back(x);
      d.steps.push_back({i, step});
    }
  }
  return d;
}

std::vector<MorrisIndex> morris_indices(const MorrisDesign& design,
                                        const std::vector<double>& outputs) {
  if (outputs.size() != design.points.size())
    throw std::invalid_argument("one output per point of the Morris design");
  std::vector<std::vector<double>> effects(std::size_t(design.parameters));
  for (std::size_t k = 1; k < outputs.size(); ++k) {
    const MorrisStep& s = design.steps[k];
    if (s.parameter < 0 || !std::isfinite(outputs[k]) || !std::isfinite(outputs[k - 1])) continue;
    effects[std::size_t(s.parameter)].push_back((outputs[k] - outputs[k - 1]) / s.delta);
  }
  std::vector<MorrisIndex> out(std::size_t(design.parameters));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::vector<double>& e = effects[i];
    MorrisIndex& m = out[i];
    m.effects = int(e.size());
    if (e.empty()) {
      m.mu = m.mu_star = m.sigma = std::nan("");
      continue;
    }
    for (double v : e) {
      m.mu += v / double(e.size());
      m.mu_star += std::abs(v) / double(e.size());
    }
    double ss = 0.0;
    for (double v : e) ss += (v - m.mu) * (v - m.mu);
    m.sigma = e.size() > 1 ? std::sqrt(ss / double(e.size() - 1)) : 0.0;
  }
  return out;
}

}  // namespace handlab::studies
