// The scripted pinch-and-lift the simulator is tested and measured on: the study hand, palm
// down, comes down over a cube on the floor, closes thumb and index on two opposite faces
// (target poses from inverse kinematics on the finger pads), lifts it 10 cm, holds it 5 s and
// opens. run_pinch steps the simulator through it and reports whether the cube was held, how
// far it slipped between the fingers, how deep the flesh went into it, and the step times.
// A client of the simulator (in its namespace), kept out of its stages in core/sim.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/hand/skeleton.h"
#include "core/sim/hand_simulator.h"
#include "core/task/grasp_closing.h"
#include "core/task/pinch_posture.h"
#include "core/task/tracker_jitter.h"

namespace handlab::sim {

struct PinchScript {
  double cube_size = 0.01;                                // m
  Eigen::Vector3d cube_centre = Eigen::Vector3d::Zero();  // at the start, on the floor
  hand::HandPose open, pinch;  // above the cube: fingers around it, pads on its faces
  // Timeline (s): open the fingers `approach_height` above the cube (5 cm, more where the
  // shaping would sweep the hand through the cube), come down, close, settle, lift 10 cm, hold
  // 5 s, open, let the cube fall.
  double shape_end = 0.3, approach_end = 0.8, close_end = 1.3, lift_start = 1.5, lift_end = 2.5;
  double hold_end = 7.5, release_end = 7.9, end = 8.7;
  double approach_height = 0.05, lift_height = 0.10;  // m
  double squeeze = 0.0;  // m: how far inside the faces the pads' targets are
  PinchPosture posture = PinchPosture::kSolved;  // how the pinch was placed (pinch_posture.h)
  // s per degree of freedom: how much later than the others it starts to close (one digit
  // before the other); empty: all together.
  std::vector<double> dof_delay;
  // A recording's tracker jitter on every pose, `jitter_scale` times (none when null).
  std::shared_ptr<const PoseJitter> jitter;
  double jitter_scale = 0.0;
  double jitter_start = 0.0;  // s into the recording at t = 0
  // A real closing in place of the scripted one (recorded_pinches.h): the hand shapes into
  // `open`, the first of these poses, and comes down onto it as the script does; from
  // approach_end to close_end it takes the latest pose at or before t - approach_end (s, the
  // first at 0); `pinch`, the last, is what the lift carries up.
  std::vector<double> recorded_times;
  std::vector<hand::HandPose> recorded_poses;
  int thumb_bone = -1, index_bone = -1;  // the distal bones that hold the cube
  double pinch_error = 0.0;  // m: the pads' targets the closed pose misses by (inverse kinematics)
  // The nearest skin but the pads' to the cube or the column under it (placement_clearance) at
  // the pinch before the closing's squeeze (m; below 0: inside), whether the hand was placed
  // again by the pinch's rule because the script's pose laid a finger inside them
  // (pinch_clearance.h), and whether the rule was then met (false where it was not needed). A
  // recorded closing's script (recorded_pinches.h) sets the clearance alone, to the cube alone
  // (skin_clearance), at its least aperture.
  double pinch_clearance = 0.0;
  bool placed_by_rule = false, pinch_meets_rule = false;
  double placement_pad_error = 0.0;  // m: the farther pad from its face's goal, so placed
  // Whether this is the scripted pinch's placement, not yet timed: what place_grasp gives the
  // default closing (make_pinch_script's at its default squeeze), which a map shares.
  bool scripted_placement = false;
  // The nearest skin of the open pose, the pads' too, to the cube or the column under it where
  // the hand aims at it (m; below 0: inside): aimed at kDescentClearance where the rule placed the
  // hand (pinch_clearance.h), short of it where the fingers alone cannot clear their knuckles.
  double open_clearance = 0.0;

  hand::HandPose target(double t) const;  // the intermediate hand at time t
  Eigen::Isometry3d start_root() const;   // the wrist at t = 0
};

// The script for the model's cube and a skeleton (the simulated hand's, whose flesh the model
// holds: the pads' depth is read from its rest nodes). `squeeze`: the pads' targets lie this
// far inside the faces, so that the tracking springs press them on.
PinchScript make_pinch_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                              double squeeze = 0.003, PinchPosture posture = PinchPosture::kSolved);

// The same pinch-and-lift closed as `closing` says (grasp_closing.h): the pads' targets
// `over_closure` past the faces along the tilted axis, moved along the faces, one digit
// `lead_s` before the other, at `closing_speed`, held `hold_s`. The default closing is the
// scripted pinch, the same poses and timeline to the bit. A closing with jitter takes it from
// `jitter` (throws std::invalid_argument without one).
PinchScript make_grasp_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                              const GraspClosing& closing,
                              std::shared_ptr<const PoseJitter> jitter = nullptr,
                              PinchPosture posture = PinchPosture::kSolved);

// make_grasp_script in two parts, so that a map places each distinct placement once. The
// placement (the poses, the clearances) reads the closing's over_closure, tilt and offset alone:
// closings with `same_placement` share it. `time_grasp` then times `placed` (place_grasp's for a
// closing with the same placement as `closing`: its timing reads the over-closure too), lays the
// jitter on and moves the cube as `closing` says.
bool same_placement(const GraspClosing& a, const GraspClosing& b);
PinchScript place_grasp(const hand::Skeleton& skeleton, const HandSimModel& model,
                        const GraspClosing& closing, PinchPosture posture = PinchPosture::kSolved);
PinchScript time_grasp(PinchScript placed, const hand::Skeleton& skeleton,
                       const GraspClosing& closing,
                       std::shared_ptr<const PoseJitter> jitter = nullptr);

// The grip at a state: over the cube's pairs of opposite faces, the lesser of the two faces'
// flesh normal forces (N).
double grip_force(const HandSimModel& model, const HandSimState& state);

// How far the cube has turned from its start, which every script sets unturned (degrees).
double cube_turn_deg(const HandSimState& state);

struct PinchReport {
  bool held = false;      // lifted to at least half the lift and kept there through the hold
  bool released = false;  // back on the floor, no flesh touching it, at the end
  double lift = 0.0;      // m: the cube's rise at the end of the hold
  double slip_mm = 0.0;   // the cube's largest displacement between the pads during the hold
  double max_penetration_mm = 0.0;  // deepest flesh node inside the cube during the hold
  // The hold's largest grip: over the cube's pairs of opposite faces, the lesser of the two
  // faces' flesh normal forces (contact_forces.h), N.
  double peak_grip_n = 0.0;
  double turn_deg = 0.0;  // how far the cube turned from its start by the end of the hold
  // The flesh's largest force on the cube's top (its own +y face) before the closing begins: a
  // hand come down onto the cube pressing it into the floor (N).
  double top_load_before_closing_n = 0.0;
  // The most flesh tets inside out at once over the run (inverted_tets.h): a flesh tangled
  // by the posture it is asked for.
  int inverted_tets = 0;
  std::vector<double> step_ms;  // wall time of every step
  std::vector<int> newton_iterations, linear_iterations, factorizations, contacts;  // per step
  std::vector<int> halvings, direct_solves, failed_cg;                              // per step
  std::vector<std::array<double, kStepTimers>> timer_ms;  // per step (SimStepReport::timer_ms)
};

// The measures of the report, fed the state after each step: the top's load before the
// closing, held, lift, slip and penetration through the hold, released at the end. run_pinch feeds
// it handlab's states; a peer simulator's run of the same script is measured by the same rules
// (tests/bench).
class PinchMeter {
 public:
  PinchMeter(const HandSimModel& model, const PinchScript& script);
  // After the step that reached time t; `max_penetration` (m) the deepest flesh node inside the
  // cube after it.
  void observe(const HandSimState& state, double t, double max_penetration);
  // At the end of a run of `duration` s: `flesh_on_cube`, whether any flesh still touches it.
  void finish(const HandSimState& state, double duration, bool flesh_on_cube,
              PinchReport& report) const;

 private:
  const HandSimModel& model_;
  const PinchScript& script_;
  bool holding_ = true, reference_set_ = false;
  Eigen::Vector3d reference_ = Eigen::Vector3d::Zero();
  double lift_ = 0.0, slip_mm_ = 0.0, max_penetration_mm_ = 0.0, peak_grip_n_ = 0.0;
  double turn_deg_ = 0.0, top_load_before_closing_n_ = 0.0;
  int inverted_tets_ = 0;
};

// The steps run_pinch takes to reach `duration` seconds, steps of `time_step`.
int pinch_step_count(double duration, double time_step);

// Runs the script up to `duration` seconds (its end when 0). `observer`, if given, sees the
// state after every step.
PinchReport run_pinch(const HandSimModel& model, const hand::Skeleton& skeleton,
                      const PinchScript& script, const SimOptions& options = {},
                      double duration = 0.0,
                      const std::function<void(const HandSimState&)>& observer = {});

}  // namespace handlab::sim
