// handlab-cli participant: enrol a participant (their schedule is fixed at enrolment).
#include <algorithm>
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_store.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_runner.h"

namespace handlab::cli {
namespace {

std::vector<OptionSpec> participant_add_options() {
  return {
      {"db", "DB", "the study database"},
      {"id", "ID", "participant id, e.g. P01"},
      {"age", "YEARS", "age in years"},
      {"sex", "F|M|X", "F, M, or X (other or not given)"},
      {"handedness", "right|left|ambidextrous", "dominant hand"},
      {"hand-length", "M", "wrist crease to middle fingertip, metres (e.g. 0.188)"},
      {"vr-experience", "TEXT", "e.g. none, some, yes, expert"},
      {"notes", "TEXT", "free text"},
  };
}

CommandHelp participant_add_help() {
  return {"participant add",
          {"db id age sex handedness hand-length vr-experience [notes]"},
          "Enrols a participant and stores their schedule, drawn from the study's seed and the "
          "id."};
}

int participant_add(const std::vector<std::string>& argv) {
  const Arguments args(participant_add_options(), argv);
  if (args.help_requested()) return print_help(participant_add_help(), args);
  args.require({"db", "id", "age", "sex", "handedness", "hand-length", "vr-experience"});
  store::Participant p;
  p.id = args.text("id");
  const long age = args.integer("age");
  p.age = int(std::clamp(age, -1L, 1000L));
  p.sex = args.text("sex");
  p.handedness = args.text("handedness");
  p.hand_length = args.number("hand-length");
  p.vr_experience = args.text("vr-experience");
  p.notes = args.text("notes");
  // The enrolment's own checks (the app's form uses them too), named by the option: the
  // values first, then, with the study's protocol, the groups they decide.
  auto refuse_problems = [](const std::vector<studies::FieldProblem>& problems,
                            const std::string& hint) {
    if (problems.empty()) return;
    std::string option = problems.front().field;
    std::replace(option.begin(), option.end(), '_', '-');
    throw UsageError("--" + option + ": " + problems.front().message +
                     (option == "hand-length" ? hint : ""));
  };
  refuse_problems(studies::participant_problems(p, {}), " Give it in metres (e.g. 0.188).");
  store::StudyStore store(args.text("db"));
  const studies::Protocol protocol = studies::stored_protocol(store);
  refuse_problems(studies::participant_problems(p, {}, &protocol), "");

  const int planned = studies::enrol_participant(store, p);
  const store::Participant enrolled = *store.participant(p.id);
  std::string groups;
  for (const auto& [factor, level] : enrolled.between_levels) groups += ", " + factor + " " + level;
  std::cout << "enrolled " << p.id << " (participant " << enrolled.enrolment + 1 << groups
            << "): " << planned << " trials planned\n";
  return 0;
}

}  // namespace

int run_participant(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::cout << family_usage({{participant_add_help(), participant_add_options()}});
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "add") return participant_add(rest);
  throw UsageError("unknown participant command '" + argv[0] + "' (add)");
}

}  // namespace handlab::cli
