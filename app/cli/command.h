// A handlab-cli subcommand: its name, a one-line summary, and what it runs.
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

struct Command {
  std::string name;
  std::string summary;
  // Receives the arguments after the command name; returns the exit status. Throws
  // UsageError for calling mistakes and std::exception for failures.
  int (*run)(const std::vector<std::string>& args);
};

// Every command, in the order --help lists them.
const std::vector<Command>& all_commands();

}  // namespace handlab::cli
