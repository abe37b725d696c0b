#include "app/cli/command_help.h"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace handlab::cli {
namespace {

const OptionSpec* find(const std::vector<OptionSpec>& options, const std::string& name) {
  const auto it = std::find_if(options.begin(), options.end(),
                               [&](const OptionSpec& o) { return o.name == name; });
  return it == options.end() ? nullptr : &*it;
}

// An option's name, or a word written as it is: operands are upper case or hold a dot.
bool is_name(const std::string& word) {
  return !word.empty() && word != "options" && std::islower(static_cast<unsigned char>(word[0])) &&
         word.find('.') == std::string::npos;
}

// "--name VALUE" ("..." after a repeatable one's, unless its value ends in one), or the word
// itself.
std::string spelled(const std::string& word, const std::vector<OptionSpec>& options,
                    const std::string& command) {
  if (!is_name(word)) return word;
  const OptionSpec* o = find(options, word);
  if (!o) throw std::logic_error(command + "'s usage names --" + word + ", which it lacks");
  const bool dotted =
      o->value_name.size() >= 3 && o->value_name.compare(o->value_name.size() - 3, 3, "...") == 0;
  return "--" + o->name + (o->value_name.empty() ? "" : " " + o->value_name) +
         (o->repeatable && !dotted ? "..." : "");
}

// One form: its words, each group's alternatives spelled and joined by " | ".
std::string form_line(const std::string& form, const std::vector<OptionSpec>& options,
                      const std::string& command) {
  std::istringstream words(form);
  std::string word, line;
  while (words >> word) {
    const char open = word.front(), close = word.back();
    const bool group = (open == '[' && close == ']') || (open == '(' && close == ')');
    std::string inner = group ? word.substr(1, word.size() - 2) : word, out;
    for (std::size_t start = 0; start <= inner.size();) {
      const std::size_t bar = std::min(inner.find('|', start), inner.size());
      out +=
          (out.empty() ? "" : " | ") + spelled(inner.substr(start, bar - start), options, command);
      start = bar + 1;
    }
    line += (line.empty() ? "" : " ") + (group ? std::string(1, open) + out + close : out);
  }
  return line;
}

}  // namespace

std::string usage_lines(const CommandHelp& help, const std::vector<OptionSpec>& options) {
  std::vector<std::string> lines;
  for (const std::string& form : help.forms)
    lines.push_back(form_line(form, options, help.command));
  if (lines.empty()) lines.push_back("[options]");
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i)
    out += std::string(i == 0 ? "Usage: " : "       ") + "handlab-cli " + help.command + " " +
           lines[i] + "\n";
  return out;
}

std::string help_text(const CommandHelp& help, const std::vector<OptionSpec>& options) {
  return usage_lines(help, options) + "\n" + help.about + "\n\nOptions:\n" +
         format_options_help(options);
}

int print_help(const CommandHelp& help, const Arguments& args) {
  std::cout << help_text(help, args.options());
  return 0;
}

std::string family_usage(const std::vector<Subcommand>& subcommands) {
  std::string out;
  for (const Subcommand& c : subcommands) {
    std::string lines = usage_lines(c.help, c.options);
    if (!out.empty()) lines.replace(0, 6, 6, ' ');  // "Usage:" once, at the top
    out += lines;
  }
  return out;
}

}  // namespace handlab::cli
