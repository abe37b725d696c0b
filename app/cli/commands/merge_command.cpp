// handlab-cli merge: one study from several databases of the same protocol.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/commands/commands.h"
#include "app/cli/output_file.h"
#include "core/store/study_merge.h"
#include "core/util/json_writer.h"

namespace handlab::cli {

int run_merge(const std::vector<std::string>& argv) {
  const std::vector<OptionSpec> specs = {
      {"out", "STUDY.db", "the merged study database to create (must not exist)"},
      {"json", "OUT", "write what was merged as JSON (- for standard output)"},
  };
  const Arguments args(specs, argv, 100000);
  if (args.help_requested()) {
    std::cout << "Usage: handlab-cli merge --out STUDY.db PART.db...\n\n"
                 "One study from several databases of the same protocol: the shards of a "
                 "simulated study (simulate --shard, --slurm) or a study recorded on several lab "
                 "machines. Every participant comes with everything stored of them (schedule, "
                 "sessions, attempts, redos and skips with their reasons, events, frames, "
                 "answers). The parts are opened read-only; the output appears only when "
                 "complete. Refused when the output exists, a part is not an intact handlab "
                 "study, the protocols differ, or a participant is in two parts with different "
                 "data (docs/cluster.md).\n\nOptions:\n"
              << format_options_help(specs);
    return 0;
  }
  args.require({"out"});
  if (args.positional().empty()) throw UsageError("name the study databases to merge");
  const std::string out = args.text("out");
  const store::MergeResult result = store::merge_studies(args.positional(), out);
  if (args.text("json") != "-")
    std::cout << result.participants << " participants from " << args.positional().size()
              << " parts into " << out
              << (result.duplicates ? " (" + std::to_string(result.duplicates) +
                                          " found twice with the same data)"
                                    : std::string())
              << (result.renumbered ? "; enrolment renumbered part by part" : "") << "\n";
  if (args.has("json"))
    write_output(args.text("json"), [&](std::ostream& os) {
      util::JsonWriter w(os);
      w.begin_object()
          .field("out", out)
          .field("parts", int(args.positional().size()))
          .field("participants", result.participants)
          .field("duplicates", result.duplicates)
          .field("renumbered", result.renumbered)
          .end_object();
      os << "\n";
    });
  return 0;
}

}  // namespace handlab::cli
