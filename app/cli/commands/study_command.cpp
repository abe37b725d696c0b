// handlab-cli study: create a study database from a protocol; show its progress.
#include <iostream>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_store.h"
#include "core/util/count_text.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"
#include "studies/export/study_export.h"
#include "studies/session/session_runner.h"

namespace handlab::cli {
namespace {

std::vector<OptionSpec> study_create_options() {
  return {
      {"protocol", "FILE", "the study protocol (JSON; docs/study.md)"},
      {"db", "DB", "the study database to create (must not exist)"},
  };
}

CommandHelp study_create_help() {
  return {"study create",
          {"protocol db"},
          "Creates a study database holding the protocol's exact text and SHA-256."};
}

int study_create(const std::vector<std::string>& argv) {
  const Arguments args(study_create_options(), argv);
  if (args.help_requested()) return print_help(study_create_help(), args);
  args.require({"protocol", "db"});
  const studies::Protocol protocol = studies::read_protocol(args.text("protocol"));
  store::StudyStore::create(args.text("db"), studies::study_definition(protocol));
  store::StudyStore created(args.text("db"));
  const store::StudyInfo info = created.study();
  std::cout << "created " << args.text("db") << ": study " << info.name << ", "
            << info.conditions.size() << " conditions, " << protocol.blocks
            << " blocks, protocol sha256 " << info.protocol_sha256 << "\n";
  return 0;
}

std::vector<OptionSpec> study_status_options() {
  return {
      {"db", "DB", "the study database"},
      {"json", "OUT", "write the status as JSON (- for standard output)"},
  };
}

CommandHelp study_status_help() {
  return {"study status",
          {"db [json]"},
          "Per participant: trials planned, completed (ended by success or timeout), skipped, "
          "aborted (interrupted attempts, run again) and the next trial."};
}

void print_status(const store::StudyInfo& info, const std::string& db,
                  const std::vector<studies::ParticipantStatus>& status,
                  const store::StudyCompleteness& completeness) {
  std::cout << "study " << info.name << " (" << db << "), "
            << util::count_text(int(status.size()), "participant") << "\n";
  if (completeness.partial())
    std::cout << "partial study: " << completeness.describe()
              << "; merge the missing parts in (merge --update, docs/cluster.md)\n";
  for (const auto& p : status) {
    std::cout << "  " << p.id << ": " << p.trials_completed << "/" << p.trials_planned
              << " completed, " << p.trials_skipped << " skipped, " << p.trials_aborted
              << " aborted, next: ";
    if (p.next)
      std::cout << "trial " << p.next->position + 1
                << (p.next->practice ? " (practice) "
                                     : " (block " + std::to_string(p.next->block) + ") ")
                << p.next_condition << "\n";
    else
      std::cout << "none (schedule complete)\n";
  }
}

void write_status_json(std::ostream& out, const store::StudyInfo& info,
                       const std::vector<studies::ParticipantStatus>& status,
                       const store::StudyCompleteness& completeness) {
  util::JsonWriter w(out);
  w.begin_object().field("study", info.name).field("protocol_sha256", info.protocol_sha256);
  w.field("partial", completeness.partial()).field("planned_participants", completeness.planned);
  w.key("missing_places").begin_array();
  for (int place : completeness.missing_places) w.value(place + 1);
  w.end_array();
  w.key("participants").begin_array();
  for (const auto& p : status) {
    w.begin_object()
        .field("id", p.id)
        .field("trials_planned", p.trials_planned)
        .field("trials_completed", p.trials_completed)
        .field("trials_skipped", p.trials_skipped)
        .field("trials_aborted", p.trials_aborted);
    w.key("next");
    if (p.next) {
      w.begin_object()
          .field("trial", p.next->position + 1)
          .field("block", p.next->block)
          .field("order", p.next->order)
          .field("practice", p.next->practice)
          .field("condition", p.next_condition)
          .end_object();
    } else {
      w.null();
    }
    w.end_object();
  }
  w.end_array().end_object();
  out << "\n";
}

int study_status(const std::vector<std::string>& argv) {
  const Arguments args(study_status_options(), argv);
  if (args.help_requested()) return print_help(study_status_help(), args);
  args.require({"db"});
  store::StudyStore store(args.text("db"));
  const store::StudyInfo info = store.study();
  const std::vector<studies::ParticipantStatus> status = studies::study_status(store);
  const store::StudyCompleteness completeness = store.completeness();
  const std::string json = args.text("json");
  if (json != "-") print_status(info, args.text("db"), status, completeness);
  if (!json.empty())
    util::write_output(
        json, [&](std::ostream& out) { write_status_json(out, info, status, completeness); });
  return 0;
}

std::vector<OptionSpec> study_info_options() {
  return {
      {"db", "DB", "the study database"},
      {"json", "OUT", "write it as JSON (- for standard output)"},
  };
}

CommandHelp study_info_help() {
  return {"study info",
          {"db [json]"},
          "The study: its name, protocol (SHA-256), seed, conditions, planned size, the file's "
          "schema, and each handlab version and commit that created it or opened it with write "
          "access."};
}

int study_info(const std::vector<std::string>& argv) {
  const Arguments args(study_info_options(), argv);
  if (args.help_requested()) return print_help(study_info_help(), args);
  args.require({"db"});
  store::StudyStore store(args.text("db"), store::StudyStore::Access::kReadOnly);
  const store::StudyInfo info = store.study();
  const std::string json = args.text("json");
  if (json != "-") {
    std::cout << "study " << info.name << " (" << args.text("db") << ")\n"
              << "  created " << info.created_at << ", schema " << info.schema_version << ", seed "
              << info.seed << "\n"
              << "  protocol sha256 " << info.protocol_sha256 << "\n"
              << "  conditions:";
    for (const auto& c : info.conditions) std::cout << ' ' << c.first;
    std::cout << "\n  planned participants: "
              << (info.planned_participants > 0 ? std::to_string(info.planned_participants)
                                                : std::string("not planned (a study of people)"))
              << "\n  written by:";
    if (info.programs.empty()) std::cout << " no version recorded (before handlab 0.28.0)";
    for (const auto& [version, commit] : info.programs)
      std::cout << "\n    handlab " << version << " (commit " << commit << ")";
    std::cout << "\n";
  }
  if (!json.empty())
    util::write_output(json, [&](std::ostream& out) {
      util::JsonWriter w(out);
      w.begin_object()
          .field("study", info.name)
          .field("created_at", info.created_at)
          .field("schema_version", info.schema_version)
          .field("seed", static_cast<unsigned long long>(info.seed))
          .field("protocol_sha256", info.protocol_sha256)
          .field("planned_participants", info.planned_participants);
      w.key("conditions").begin_array();
      for (const auto& c : info.conditions) w.value(c.first);
      w.end_array().key("programs").begin_array();
      for (const auto& [version, commit] : info.programs)
        w.begin_object().field("version", version).field("commit", commit).end_object();
      w.end_array().end_object();
    });
  return 0;
}

}  // namespace

int run_study(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    std::cout << family_usage({{study_create_help(), study_create_options()},
                               {study_status_help(), study_status_options()},
                               {study_info_help(), study_info_options()}});
    return argv.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "create") return study_create(rest);
  if (argv[0] == "status") return study_status(rest);
  if (argv[0] == "info") return study_info(rest);
  throw UsageError("unknown study command '" + argv[0] + "' (create, status, info)");
}

}  // namespace handlab::cli
