// handlab-cli merge: one study from several databases of the same protocol.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_merge.h"
#include "core/util/count_text.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::cli {

namespace {

std::vector<OptionSpec> merge_options() {
  return {
      {"out", "STUDY.db", "the merged study database to create (must not exist)"},
      {"partial", "",
       "write the study though the parts lack participants its plan names (a simulated "
       "study's missing shards); it says it is partial until merged again with the rest"},
      {"update", "",
       "OUT may exist: a partial OUT is merged again with the parts and replaced; a whole one "
       "is left as it is"},
      {"json", "OUT", "write what was merged as JSON (- for standard output)"},
  };
}

CommandHelp merge_help() {
  return {"merge",
          {"out [partial] [update] [json] PART.db..."},
          "One study from several databases of the same protocol: the shards of a simulated "
          "study (simulate --shard, --slurm) or a study recorded on several lab machines. Every "
          "participant comes with everything stored of them (schedule, sessions, attempts, redos "
          "and skips with their reasons, events, frames, answers). The parts are opened "
          "read-only; the output appears only when complete. Refused when the output exists, a "
          "part is not an intact handlab study, the protocols differ, a participant is in two "
          "parts with different data, or a simulated study's parts lack participants its plan "
          "names (unless --partial; docs/cluster.md)."};
}

}  // namespace

int run_merge(const std::vector<std::string>& argv) {
  const Arguments args(merge_options(), argv, 100000);
  if (args.help_requested()) return print_help(merge_help(), args);
  args.require({"out"});
  if (args.positional().empty()) throw UsageError("name the study databases to merge");
  const std::string out = args.text("out");
  const store::MergeResult result = store::merge_studies(
      args.positional(), out, {.partial = args.flag("partial"), .update = args.flag("update")});
  if (args.text("json") != "-" && result.whole_already)
    std::cout << out << " holds every planned participant already: nothing to merge\n";
  else if (args.text("json") != "-")
    std::cout << util::count_text(result.participants, "participant") << " from "
              << args.positional().size() << (args.positional().size() == 1 ? " part" : " parts")
              << " into " << out
              << (result.duplicates ? " (" + std::to_string(result.duplicates) +
                                          " found twice with the same data)"
                                    : std::string())
              << (result.renumbered ? "; enrolment renumbered part by part" : "") << "\n"
              << (result.completeness.partial()
                      ? "partial study: " + result.completeness.describe() +
                            "; merge the rest in with merge --update\n"
                      : "");
  if (args.has("json"))
    util::write_output(args.text("json"), [&](std::ostream& os) {
      util::JsonWriter w(os);
      w.begin_object()
          .field("out", out)
          .field("parts", int(args.positional().size()))
          .field("participants", result.participants)
          .field("duplicates", result.duplicates)
          .field("renumbered", result.renumbered)
          .field("whole_already", result.whole_already)
          .field("partial", result.completeness.partial())
          .field("planned_participants", result.completeness.planned)
          .end_object();
      os << "\n";
    });
  return 0;
}

}  // namespace handlab::cli
