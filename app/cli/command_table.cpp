#include "app/cli/command.h"
#include "app/cli/commands/commands.h"

namespace handlab::cli {

const std::vector<Command>& all_commands() {
  static const std::vector<Command> commands = {
      {"analyze", "repeated-measures ANOVA, post hoc, Friedman and Wilcoxon tests (R parity)",
       run_analyze},
      {"hand", "build the simulated hand (skin, flesh) or the tracked skeleton of a given size",
       run_hand},
      {"retarget", "retarget a recording onto the simulated hand (naive or ours) and report errors",
       run_retarget},
      {"sim",
       "the soft-hand simulator: time its steps, pinch and lift a cube over closings and real "
       "recordings, kick one (bench, pinch, grasp, pinches, replay, settle)",
       run_sim},
      {"tracking", "read Leap Motion recordings: info, convert to CSV or .hlrec", run_tracking},
      {"xr",
       "OpenXR: the runtime and headset found (list), its hands recorded (hands), the task "
       "scene shown in the headset (show)",
       run_xr},
      {"render", "draw the task scene, or a moment of a stored trial, into a PNG (no display)",
       run_render},
      {"study", "create a study database from a protocol; show its progress and what wrote it",
       run_study},
      {"participant", "enrol a participant (their schedule is fixed and stored)", run_participant},
      {"session", "run a participant's session headless (resumes after a crash); redo, skip",
       run_session},
      {"simulate",
       "run a whole study with simulated participants on the soft hand (or the grasp proxy)",
       run_simulate},
      {"merge", "one study from several databases of one protocol (shards, lab machines)",
       run_merge},
      {"power",
       "simulation-based power of a study design for every N, per effect and planned contrast",
       run_power},
      {"replications",
       "several studies of one protocol side by side: each test's distribution, the published "
       "values",
       run_replications},
      {"sensitivity",
       "how simulated studies' conclusions hang on the participant model's parameters (Morris)",
       run_sensitivity},
      {"export", "write a study's trials and questionnaires as CSV for R, JASP, jamovi",
       run_export},
      {"grasps",
       "how the grasps of logged trials met the cube (tip or pad, off centre) and which lost it",
       run_grasps},
#ifdef HANDLAB_WITH_REPORT
      {"report", "write a study's results section with tables and figures as HTML and PDF",
       run_report},
#endif
  };
  return commands;
}

}  // namespace handlab::cli
