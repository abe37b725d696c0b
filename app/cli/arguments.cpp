#include "app/cli/arguments.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <thread>

#include "app/cli/nearest_word.h"

namespace handlab::cli {

Arguments::Arguments(std::vector<OptionSpec> specs, std::vector<std::string> argv,
                     int max_positional)
    : specs_(std::move(specs)) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--help" || a == "-h") {
      help_ = true;
      continue;
    }
    if (a.rfind("--", 0) == 0 && a.size() > 2) {
      std::string name = a.substr(2);
      std::optional<std::string> inline_value;
      if (const auto eq = name.find('='); eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name.resize(eq);
      }
      const OptionSpec& s = spec(name);
      if (!s.repeatable && values_.count(name))
        throw UsageError("option --" + name + " given more than once");
      if (s.value_name.empty()) {
        if (inline_value) throw UsageError("option --" + name + " takes no value");
        values_[name].push_back("1");
      } else if (inline_value) {
        values_[name].push_back(*inline_value);
      } else {
        if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
        values_[name].push_back(argv[++i]);
      }
      continue;
    }
    if (int(positional_.size()) >= max_positional)
      throw UsageError("unexpected argument '" + a + "'");
    positional_.push_back(a);
  }
}

const OptionSpec& Arguments::spec(const std::string& name) const {
  const auto it = std::find_if(specs_.begin(), specs_.end(),
                               [&](const OptionSpec& s) { return s.name == name; });
  if (it == specs_.end()) {
    std::vector<std::string> names;
    for (const OptionSpec& s : specs_) names.push_back(s.name);
    const std::string hint = did_you_mean(name, names, "--");
    throw UsageError("unknown option --" + name + (hint.empty() ? " (see --help)" : hint));
  }
  return *it;
}

std::string Arguments::choice(const std::string& name,
                              const std::vector<std::string>& choices) const {
  const std::string value = text(name);
  if (std::find(choices.begin(), choices.end(), value) != choices.end()) return value;
  std::string list;
  for (std::size_t i = 0; i < choices.size(); ++i)
    list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  throw UsageError("--" + name + " must be " + list + ", not '" + value + "'" +
                   did_you_mean(value, choices));
}

bool Arguments::flag(const std::string& name) const {
  spec(name);
  return values_.count(name) > 0;
}

bool Arguments::has(const std::string& name) const {
  spec(name);
  return values_.count(name) > 0;
}

std::string Arguments::text(const std::string& name) const {
  const OptionSpec& s = spec(name);
  const auto it = values_.find(name);
  return it == values_.end() ? s.default_value : it->second.back();
}

std::vector<std::string> Arguments::all(const std::string& name) const {
  spec(name);
  const auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

double parse_number(const std::string& value, const std::string& what) {
  double result = 0.0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (value.empty() || error != std::errc() || end != value.data() + value.size() ||
      !std::isfinite(result))
    throw UsageError(what + " needs a number, got '" + value + "'");
  return result;
}

double Arguments::number(const std::string& name) const {
  return parse_number(text(name), "option --" + name);
}

void Arguments::require(std::initializer_list<const char*> names) const {
  for (const char* name : names)
    if (!has(name)) throw UsageError(std::string("--") + name + " is required");
}

long Arguments::integer(const std::string& name) const {
  const std::string value = text(name);
  long result = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (value.empty() || error != std::errc() || end != value.data() + value.size())
    throw UsageError("option --" + name + " needs a whole number, got '" + value + "'");
  return result;
}

std::uint64_t Arguments::seed(const std::string& name) const {
  const std::string value = text(name);
  std::uint64_t result = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (value.empty() || error != std::errc() || end != value.data() + value.size())
    throw UsageError("option --" + name + " needs a whole number from 0 to 2^64 - 1, got '" +
                     value + "'");
  return result;
}

std::string format_options_help(const std::vector<OptionSpec>& specs) {
  std::ostringstream out;
  for (const OptionSpec& s : specs) {
    std::string left = "  --" + s.name + (s.value_name.empty() ? "" : " " + s.value_name);
    if (left.size() < 26)
      left.resize(26, ' ');
    else
      left += "  ";
    out << left << s.help;
    // A help that says its default in words ("default: the machine's cores") says it once.
    if (!s.default_value.empty() && s.help.find("default:") == std::string::npos)
      out << " (default " << s.default_value << ")";
    out << "\n";
  }
  out << "  --help                  show this help\n";
  return out.str();
}

int job_count(const Arguments& args) {
  const long jobs = args.integer("jobs");
  if (jobs < 0) throw UsageError("--jobs must be 0 (all cores) or more");
  return jobs == 0 ? int(std::max(1u, std::thread::hardware_concurrency())) : int(jobs);
}

}  // namespace handlab::cli
