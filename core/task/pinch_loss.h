// Why a pinch-and-lift lost its cube (pinch_script.h), read from its run: pushed away by the
// first pad, squeezed out of the pads, or slipped at the lift. The grasp map (grasp_map.h)
// and the real pinches (recorded_pinches.h) tell their lost runs apart by it.
#pragma once

#include <optional>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/task/pinch_script.h"

namespace handlab::sim {

// The first pad pushed the cube more than a quarter of its side along the floor before the
// closing's end, with no grip at the lift's start (pushed away); no grip at the lift's start
// otherwise (squeezed out: the pads met it but did not keep it between them); a grip at the
// lift's start that the lift or the hold lost (slipped at the lift).
enum class PinchLoss { kNone, kPushedAway, kSqueezedOut, kSlippedAtLift };
const char* pinch_loss_name(PinchLoss loss);

// Watches a run's states for the loss's signs: how far the cube was pushed along the floor by
// the closing's end, and the grip as the lift starts; and how the pads met it before the lift:
// how long after the thumb's distal skin first touched the cube the index's did (below 0: the
// index's first, as the closing's lead), and the cube's turn then (none where one never did).
class PinchLossWatch {
 public:
  PinchLossWatch(const HandSimModel& model, const PinchScript& script);
  void observe(const HandSimState& state);  // the state after each step
  PinchLoss loss(bool held) const;          // of a run that held the cube or not
  double pushed_mm() const { return pushed_mm_; }
  double grip_at_lift_n() const { return grip_at_lift_n_; }
  std::optional<double> touch_lead_ms() const { return touch_lead_ms_; }
  std::optional<double> turn_at_touch_deg() const { return turn_at_touch_deg_; }

 private:
  void watch_touches(const HandSimState& s);
  bool touches(const HandSimState& s, int bone) const;  // the bone's skin on the cube

  const HandSimModel& model_;
  const PinchScript& script_;
  double pushed_mm_ = 0.0, grip_at_lift_n_ = 0.0;
  bool lift_seen_ = false;
  double thumb_touch_s_ = -1.0, index_touch_s_ = -1.0;  // < 0: not yet
  std::optional<double> touch_lead_ms_, turn_at_touch_deg_;
};

}  // namespace handlab::sim
