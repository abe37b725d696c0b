// Morris's elementary effects (Morris 1991, Technometrics 33:161; the screening statistics of
// Campolongo, Cariboni & Saltelli 2007, Environ. Model. Softw. 22:1509): r trajectories through
// the unit cube of k parameters on a grid of p levels, each moving one parameter at a time by
// delta = p / (2 (p - 1)); a parameter's elementary effect is the output's change over its
// step. mu* (the mean of their absolute values) ranks how much an output hangs on the
// parameter, sigma (their SD) how far the effect depends on the others or is not linear.
#pragma once

#include <cstdint>
#include <vector>

namespace handlab::studies {

struct MorrisStep {
  int parameter = -1;  // the one changed since the trajectory's previous point (-1: its first)
  double delta = 0.0;  // by how much, in the unit cube (+ or - the grid's delta)
};

struct MorrisDesign {
  int parameters = 0, levels = 0;
  // r (k + 1) points in [0, 1]^k, trajectory after trajectory, each point with its step.
  std::vector<std::vector<double>> points;
  std::vector<MorrisStep> steps;
};

// Throws std::invalid_argument unless parameters >= 1, trajectories >= 2 and levels is even
// and >= 2. The same seed gives the same design.
MorrisDesign morris_design(int parameters, int trajectories, int levels, std::uint64_t seed);

struct MorrisIndex {
  double mu = 0.0;       // mean elementary effect (signed)
  double mu_star = 0.0;  // mean of the absolute elementary effects
  double sigma = 0.0;    // their SD (n - 1)
  int effects = 0;       // elementary effects with a finite output on both sides
};

// Per parameter, from the output at each point of the design (in the design's order; a NaN
// output leaves out the elementary effects it takes part in). Effects are per unit of the
// cube: scale by the parameter's range for its own units.
std::vector<MorrisIndex> morris_indices(const MorrisDesign& design,
                                        const std::vector<double>& outputs);

}  // namespace handlab::studies
