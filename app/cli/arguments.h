// Parsing of "--name value", "--flag" and positional arguments against declared options,
// with the --help text generated from the same declarations.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace handlab::cli {

// A mistake in how the command was called: reported on one line with exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  OptionSpec(std::string name_, std::string value_name_, std::string help_,
             std::string default_value_ = {}, bool repeatable_ = false)
      : name(std::move(name_)),
        value_name(std::move(value_name_)),
        help(std::move(help_)),
        default_value(std::move(default_value_)),
        repeatable(repeatable_) {}

  std::string name;        // without the leading "--"
  std::string value_name;  // empty for a flag
  std::string help;
  std::string default_value;  // what text() returns when the option is absent
  bool repeatable;
};

// `value` as a finite number; UsageError "WHAT needs a number, not 'VALUE'" otherwise.
double parse_number(const std::string& value, const std::string& what);

class Arguments {
 public:
  Arguments(std::vector<OptionSpec> specs, std::vector<std::string> argv, int max_positional = 0);

  bool flag(const std::string& name) const;
  bool has(const std::string& name) const;
  // Throws UsageError naming the first of these options that was not given.
  void require(std::initializer_list<const char*> names) const;
  std::string text(const std::string& name) const;  // the value or the declared default
  // text(), which must be one of `choices`; else UsageError listing them, with a hint for a
  // misspelling ("did you mean soft?").
  std::string choice(const std::string& name, const std::vector<std::string>& choices) const;
  std::vector<std::string> all(const std::string& name) const;
  double number(const std::string& name) const;
  long integer(const std::string& name) const;
  // A seed: any 64-bit unsigned whole number.
  std::uint64_t seed(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }
  bool help_requested() const { return help_; }
  const std::vector<OptionSpec>& options() const { return specs_; }  // as declared

 private:
  const OptionSpec& spec(const std::string& name) const;
  std::vector<OptionSpec> specs_;
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
  bool help_ = false;
};

std::string format_options_help(const std::vector<OptionSpec>& specs);

// --jobs J: runs side by side, 0 for the machine's cores; throws UsageError below 0.
int job_count(const Arguments& args);

}  // namespace handlab::cli
