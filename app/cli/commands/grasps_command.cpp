// handlab-cli grasps: how the grasps of a study's logged trials met the cube, and which lost
// it, from the frame logs.
#include <array>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include "app/cli/arguments.h"
#include "app/cli/command_help.h"
#include "app/cli/commands/commands.h"
#include "core/store/study_store.h"
#include "core/util/output_file.h"
#include "studies/analysis/grasp_tally.h"

namespace handlab::cli {
namespace {

std::string share(const studies::GraspCount& c) {
  char text[64];
  if (c.grasps == 0) return "none";
  std::snprintf(text, sizeof text, "%d of %d (%.0f %%)", c.lost, c.grasps,
                100.0 * c.lost / c.grasps);
  return text;
}

std::string edge(double x) {
  char text[16];
  std::snprintf(text, sizeof text, "%.1f", x);
  return text;
}

void print_by_part(const char* digit, const std::array<studies::GraspCount, 3>& by_part) {
  std::cout << "    " << digit << ":";
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
  std::cout << t.group << ": " << t.grasps << " grasps in " << t.trials << " trials; lost "
            << share({t.grasps, t.lost()}) << " (dropped " << t.dropped << ", landed and grasped "
            << "again " << t.landed << "); placed " << t.placed << ", caught in the air "
            << t.caught_again << ", unfinished " << t.unfinished << "\n";
  std::cout << "  lost, by the part of the distal phalanx nearest the cube's centre:\n";
  print_by_part("thumb", t.by_thumb);
  print_by_part("index", t.by_index);
  const auto& e = studies::kPinchOffsetEdges;
  std::cout << "  lost, by the pinch's distance from the cube's centre along the floor (share "
               "of the side):\n    < "
            << edge(e[0]) << ": " << share(t.by_offset[0]) << ", " << edge(e[0]) << "-"
            << edge(e[1]) << ": " << share(t.by_offset[1]) << ", >= " << edge(e[1]) << ": "
            << share(t.by_offset[2]) << "\n";
  const studies::FactorSpread root = studies::spread_of(t.jitter_root_rms, 1e-3),
                              angle = studies::spread_of(t.jitter_angle_rms, M_PI / 180);
  if (root.n > 0)
    std::printf(
        "  the intermediate hand's jitter (RMS of what its 0.1 s average leaves; sim grasp's "
        "jitter), median [10th-90th percentile] of the trials: the wrist %.3g [%.3g, %.3g] "
        "mm, the joints %.3g [%.3g, %.3g] deg\n",
        root.median, root.p10, root.p90, angle.median, angle.p10, angle.p90);
  if (t.kept_closings.empty() && t.lost_closings.empty()) return;
  std::printf(
      "  closings in the grasp map's terms (sim grasp), median [10th-90th percentile]:\n"
      "    %-16s %-28s %s\n",
      "", ("kept (" + std::to_string(t.kept_closings.size()) + ")").c_str(),
      ("lost (" + std::to_string(t.lost_closings.size()) + ")").c_str());
  for (const studies::LoggedFactor& f : studies::logged_factors()) {
    auto spread = [&](const std::vector<studies::LoggedClosing>& closings) {
      const studies::FactorSpread s = studies::factor_spread(closings, f);
      char text[80];
      if (s.n == 0) return std::string("-");
      std::snprintf(text, sizeof text, "%.3g [%.3g, %.3g] %s", s.median, s.p10, s.p90, f.unit);
      return std::string(text);
    };
    std::printf("    %-16s %-28s %s\n", f.name, spread(t.kept_closings).c_str(),
                spread(t.lost_closings).c_str());
  }
}

}  // namespace

namespace {

std::vector<OptionSpec> grasps_options() {
  return {
      {"db", "DB", "the study database (its trials run with logged frames)"},
      {"participant", "ID", "only this participant's trials"},
      {"by", "cube|condition", "group the grasps by the cube's size or by condition", "cube"},
      {"json", "OUT", "write the groups and every grasp as JSON (- for standard output)"},
  };
}

CommandHelp grasps_help() {
  return {"grasps",
          {"db [participant] [by] [json]"},
          "How each grasp of the study's trials met the cube, from their frame logs (trials with "
          "a result whose attempt logged frames, practice included: a session's, or a simulated "
          "study run with --frames). At the first frame the task saw the cube lifted between "
          "thumb and index: on each distal phalanx, the point of the bone nearest the cube's "
          "centre (the fingertip's end: tip; the joint: base; between: pad), and the pinch's "
          "midpoint against the cube's centre. Then what became of the grasp: placed in B, "
          "dropped (it came to rest outside B), landed (it came down onto the floor and was "
          "grasped again before it rested), caught again in the air, or unfinished at the "
          "trial's end. Prints per group how many grasps lost the cube (dropped or landed) by "
          "the part of each phalanx and by the pinch's distance from the centre; --json writes "
          "the same and every grasp, and with - replaces the printout (docs/study.md)."};
}

}  // namespace

int run_grasps(const std::vector<std::string>& argv) {
  const Arguments args(grasps_options(), argv);
  if (args.help_requested()) return print_help(grasps_help(), args);
  args.require({"db"});
  const std::string by = args.choice("by", {"cube", "condition"});
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
    util::write_output(args.text("json"), [&](std::ostream& out) {
      util::JsonWriter w(out);
      studies::write_grasps_json(w, trials, tallies);
      out << "\n";
    });
  return 0;
}

}  // namespace handlab::cli
