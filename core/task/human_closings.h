// A distribution of people's closings on a cube they see but do not feel: each factor of
// GraspClosing drawn as the table of human_closing_parameters() says, with where each value
// comes from (a primary source, or an assumption where none measured it). The grasp map runs
// draws of it beside its grid (`sim grasp --draws`, docs/simulator.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/task/grasp_map.h"

namespace handlab::sim {

struct ClosingParameter {
  std::string factor;        // a closing factor's name (grasp_closing.h)
  std::string distribution;  // in the factor's unit
  std::string source;        // author, year, table or figure, condition
  bool assumption = true;    // no measured value behind the numbers
};
const std::vector<ClosingParameter>& human_closing_parameters();

// `count` closings drawn for a cube of `cube_size` (m) from `seed`, each with `jitter` times a
// recording's tracker jitter (1 with one: its own; 0 without) from a stretch of it of its
// own; factor "draw", level the draw's number (1, 2, ...). The same seed gives the same closings on
// every platform.
std::vector<ClosingPoint> human_closing_draws(int count, std::uint64_t seed, double cube_size,
                                              double jitter = 0.0);

}  // namespace handlab::sim
