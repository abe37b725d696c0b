// handlab-cli grasps: how the grasps of a study's logged trials met the cube, and which were
// dropped, from the frame logs.
#include <array>
#include <cstdio>
#include <iostream>
#include <string>

#include "app/cli/arguments.h"
#include "app/cli/commands/commands.h"
#include "app/cli/output_file.h"
#include "core/store/study_store.h"
#include "studies/analysis/grasp_tally.h"

namespace handlab::cli {
namespace {

std::string share(const studies::GraspCount& c) {
  char text[64];
  if (c.grasps == 0) return "0 of 0";
  std::snprintf(text, sizeof text, "%d of %d (%.0f %%)", c.dropped, c.grasps,
                100.0 * c.dropped / c.grasps);
  return text;
}

void print_by_part(const char* digit, const std::array<studies::GraspCount, 3>& by_part) {
  std::cout << "  dropped, by the part of the " << digit << " nearest the cube:";
  const char* sep = " ";
  for (auto part :
       {studies::PhalanxPart::kPad, studies::PhalanxPart::kTip, studies::PhalanxPart::kBase}) {
    const studies::GraspCount& c = by_part[std::size_t(part)];
    if (c.grasps == 0) continue;
    std::cout << sep << studies::phalanx_part_name(part) << " " << share(c);
    sep = ", ";
  }
  std::cout << "\n";
}

void print_tally(const studies::GraspTally& t) {
  std::cout << t.group << ": " << t.grasps << " grasps in " << t.trials << " trials; placed "
            << t.placed << ", dropped " << share({t.grasps, t.dropped}) << ", caught again "
            << t.caught_again << ", unfinished " << t.unfinished << "\n";
  print_by_part("thumb", t.by_thumb);
  print_by_part("index", t.by_index);
  const auto& b = studies::kPinchOffsetBounds;
  auto bound = [](double x) {
    char text[16];
    std::snprintf(text, sizeof text, "%.1f", x);
    return std::string(text);
  };
  std::cout << "  dropped, by the pinch's distance from the cube's centre along the floor "
               "(share of the side): below "
            << bound(b[0]) << " " << share(t.by_offset[0]) << ", " << bound(b[0]) << "-"
            << bound(b[1]) << " " << share(t.by_offset[1]) << ", " << bound(b[1]) << " and more "
            << share(t.by_offset[2]) << "\n";
}

}  // namespace

int run_grasps(const std::vector<std::string>& argv) {
  const std::vector<OptionSpec> specs = {
      {"db", "DB", "the study database (its trials run with logged frames)"},
      {"participant", "ID", "only this participant's trials"},
      {"by", "cube|condition", "group the grasps by the cube's size or by condition", "cube"},
      {"json", "OUT", "write the groups and every grasp as JSON (- for standard output)"},
  };
  const Arguments args(specs, argv);
  if (args.help_requested()) {
    std::cout
        << "Usage: handlab-cli grasps --db DB [--participant ID] [--by cube|condition] "
           "[--json OUT]\n\nHow each grasp of the study's trials met the cube, from their "
           "frame logs (trials with a result whose attempt logged frames: a session's, or a "
           "simulated study run with --frames): at the first frame the task saw the cube "
           "lifted between thumb and index, the part of each distal phalanx nearest the cube's "
           "centre (tip, pad or base of the bone), the pinch's midpoint against the cube's "
           "centre, and what became of the grasp (placed in B, dropped outside it, caught "
           "again, or unfinished when the trial ended). Prints per group how many grasps were "
           "dropped, by each of those (docs/study.md).\n\nOptions:\n"
        << format_options_help(specs);
    return 0;
  }
  args.require({"db"});
  const std::string by = args.text("by");
  if (by != "cube" && by != "condition") throw UsageError("--by must be cube or condition");
  store::StudyStore store(args.text("db"), store::StudyStore::Access::kReadOnly);
  const std::string participant = args.text("participant");
  if (!participant.empty() && !store.participant(participant))
    throw std::runtime_error("no participant '" + participant + "' in this study");
  const auto trials = studies::study_grasp_contacts(store, participant);
  if (trials.empty())
    throw std::runtime_error(
        "no trial with a result has logged frames (run the sessions, or "
        "simulate with --frames)");
  const auto tallies =
      studies::tally_grasps(trials, by == "condition" ? studies::GraspGrouping::kCondition
                                                      : studies::GraspGrouping::kCube);
  if (args.text("json") != "-") {
    std::cout << "Grasps of " << trials.size() << " trials with logged frames, by " << by << "\n";
    for (const studies::GraspTally& t : tallies) print_tally(t);
  }
  if (args.has("json"))
    write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter w(out);
      studies::write_grasps_json(w, trials, tallies);
      out << "\n";
    });
  return 0;
}

}  // namespace handlab::cli
