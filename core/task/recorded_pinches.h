// The grip's question asked of real hands: every closing of thumb and index in a recording,
// retargeted onto the study hand, with a cube placed where the pads reach its faces, then the
// script's lift and hold (pinch_script.h). Where the grasp map (grasp_map.h) closes as a
// distribution of people might, these close as one person did.
//
// The rules, stated once here:
// - A closing: the pads' aperture (the distance between the thumb's and the index's pads,
//   finger_pads.h, on the retargeted hand) falls to a least value at least 1 cm below the
//   largest before it (since the previous closing) and rises 1 cm after it (or the recording
//   ends): tracker jitter is under a millimetre.
// - For a cube of side s: its moment is the last frame before the least aperture at which the
//   aperture is still at least s, the pads at the faces; a closing whose largest aperture is
//   under s cannot take the cube (not run), nor one whose least is above it (the pads never
//   reach the faces).
// - The placement: the whole recorded hand is turned (the least turn) and moved so that at
//   that moment the pads' midpoint is the centre of the cube resting on the floor and the line
//   between them is the cube's z axis, level: the recordings pinch in the air, held at any
//   angle, and a person takes a cube off a floor with the pads on two side faces. The hand's
//   flesh passes through the floor, as in the study.
// - The run: the hand shapes into the pose 0.5 s before the moment 5 cm above it and comes
//   down onto it, the recording plays to the least aperture, the fingers stay there, and the
//   script's settle, lift, hold and opening follow.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/pinch_loss.h"
#include "core/task/pinch_script.h"

namespace handlab::sim {

// One closing of a recording for one cube.
struct RecordedClosing {
  int first_frame = 0;  // where the run's recording starts (0.5 s before `moment`)
  int moment_frame = 0, closed_frame = 0;
  double moment = 0.0, closed = 0.0;     // s into the recording
  double widest = 0.0, narrowest = 0.0;  // m: the aperture's largest before, least at the end
  double closing_speed = 0.0;            // m/s: each pad's approach at the moment
  double tilt = 0.0;        // rad: the pads' line from the horizontal then, before the placement
  bool takes_cube = false;  // the pads opened to the side and closed past it: run
};

// The pads' aperture (m) of each pose, on `skeleton` with `model`'s flesh.
std::vector<double> pad_apertures(const hand::Skeleton& skeleton, const HandSimModel& model,
                                  const std::vector<hand::HandPose>& poses);

// The closings of a recording's `poses` on `skeleton` at `times` (s) for `model`'s cube, by the
// rules above, those that cannot take it too.
std::vector<RecordedClosing> find_recorded_closings(const hand::Skeleton& skeleton,
                                                    const HandSimModel& model,
                                                    const std::vector<double>& times,
                                                    const std::vector<hand::HandPose>& poses);

// The script that plays `closing` of the recording (`times`, `poses` on `skeleton`) on
// `model`'s cube, placed as the rules say.
PinchScript make_recorded_pinch_script(const hand::Skeleton& skeleton, const HandSimModel& model,
                                       const std::vector<double>& times,
                                       const std::vector<hand::HandPose>& poses,
                                       const RecordedClosing& closing);

struct RecordedPinchRun {
  PinchReport report;
  PinchLoss loss = PinchLoss::kNone;
  double pushed_mm = 0.0;       // the cube's displacement along the floor by the closing's end
  double grip_at_lift_n = 0.0;  // the grip as the lift starts
  // How much later the index's pad first touched the cube than the thumb's, and the cube's turn
  // then (none: a pad never touched it before the lift; pinch_loss.h).
  std::optional<double> touch_lead_ms, turn_at_touch_deg;
};

RecordedPinchRun run_recorded_pinch(const HandSimModel& model, const hand::Skeleton& skeleton,
                                    const PinchScript& script, const SimOptions& options = {});

}  // namespace handlab::sim
