// A command's --help from its declaration: its usage lines are forms over the names of its
// option table, so each option's name and value are written once (in its OptionSpec), then
// what the command does, then the table itself.
#pragma once

#include <string>
#include <vector>

#include "app/cli/arguments.h"

namespace handlab::cli {

struct CommandHelp {
  std::string command;  // as typed after handlab-cli: "merge", "sim grasp"
  // Each a way to call it, over the table's option names: `name` is "--name VALUE", `[name]`
  // optional, `(a|b)` and `[a|b]` one of several; anything else (FILE, PART.db..., [options])
  // is written as it is. No form at all is "[options]".
  std::vector<std::string> forms;
  std::string about;  // what it does: paragraphs, blank-line separated
};

// "Usage: handlab-cli COMMAND ..." and the further forms under it, one line each. Throws
// std::logic_error for a name the table lacks (the help tests call every command's --help).
std::string usage_lines(const CommandHelp& help, const std::vector<OptionSpec>& options);

// The usage lines, the about text and the options.
std::string help_text(const CommandHelp& help, const std::vector<OptionSpec>& options);

// --help: the command's help_text on standard output; returns its exit status, 0.
int print_help(const CommandHelp& help, const Arguments& args);

// A command of a family ("study create", "sim grasp") with its option table.
struct Subcommand {
  CommandHelp help;
  std::vector<OptionSpec> options;
};

// Every subcommand's usage lines under one "Usage:": what `handlab-cli FAMILY` alone says.
std::string family_usage(const std::vector<Subcommand>& subcommands);

}  // namespace handlab::cli
