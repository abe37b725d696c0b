// Entry points of the subcommands; each parses its own arguments.
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

int run_render(const std::vector<std::string>& args);

}  // namespace handlab::cli
