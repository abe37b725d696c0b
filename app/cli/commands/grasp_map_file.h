// A grasp map as `sim grasp --json` wrote it, read back to be set beside a new run
// (`sim grasp --against`).
#pragma once

#include <string>
#include <vector>

#include "core/task/grasp_comparison.h"

namespace handlab::cli {

struct MappedCube {
  double cube_size = 0.0;  // m
  std::vector<sim::MappedClosing> closings;
};

// The cubes of the map at `path`, each closing with its factors' values and outcome; throws
// UsageError naming the file and what is missing or wrong.
std::vector<MappedCube> read_grasp_map(const std::string& path);

}  // namespace handlab::cli
