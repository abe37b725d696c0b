// handlab-cli: every handlab job, headless.
#include <algorithm>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/arguments.h"
#include "app/cli/command.h"
#include "core/util/build_info.h"

namespace {

void print_usage() {
  std::cout << "Usage: handlab-cli COMMAND [options]\n\n"
               "handlab runs and analyses user studies of fine virtual manipulation with\n"
               "tracked hands. Commands:\n\n";
  // The summaries in one column, two spaces past the longest name.
  std::size_t width = 0;
  for (const auto& c : handlab::cli::all_commands()) width = std::max(width, c.name.size());
  for (const auto& c : handlab::cli::all_commands())
    std::cout << "  " << c.name << std::string(width + 2 - c.name.size(), ' ') << c.summary << "\n";
  std::cout
      << "\n'handlab-cli COMMAND --help' describes a command. --version prints the version.\n";
}

// Messages go out on one line, whatever the exception carried (shader logs have newlines).
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_usage();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version" || args[0] == "version") {
    std::cout << "handlab-cli " << handlab::util::version_line() << "\n";
    return 0;
  }
  for (const auto& command : handlab::cli::all_commands()) {
    if (command.name != args[0]) continue;
    try {
      return command.run(std::vector<std::string>(args.begin() + 1, args.end()));
    } catch (const handlab::cli::UsageError& e) {
      std::cerr << "handlab-cli " << command.name << ": " << one_line(e.what()) << "\n";
      return 2;
    } catch (const std::filesystem::filesystem_error& e) {
      // The file system's words ("filesystem error: cannot create directories: ...") as what
      // happened to which file.
      std::cerr << "handlab-cli " << command.name << ": "
                << (e.path1().empty() ? std::string("a file") : "cannot use " + e.path1().string())
                << (e.path2().empty() ? "" : " or " + e.path2().string()) << ": "
                << e.code().message() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "handlab-cli " << command.name << ": " << one_line(e.what()) << "\n";
      return 1;
    }
  }
  std::cerr << "handlab-cli: unknown command '" << args[0] << "' (see handlab-cli --help)\n";
  return 2;
}
