#include "core/task/pinch_loss.h"

#include <algorithm>
#include <cmath>

namespace handlab::sim {

const char* pinch_loss_name(PinchLoss loss) {
  switch (loss) {
    case PinchLoss::kNone:
      return "held";
    case PinchLoss::kPushedAway:
      return "pushed_away";
    case PinchLoss::kSqueezedOut:
      return "squeezed_out";
    case PinchLoss::kSlippedAtLift:
      return "slipped_at_lift";
  }
  return "?";
}

PinchLossWatch::PinchLossWatch(const HandSimModel& model, const PinchScript& script)
    : model_(model), script_(script) {}

bool PinchLossWatch::touches(const HandSimState& s, int bone) const {
  const auto on = [&](int node) {  // a model without bones has no node_bone
    return std::size_t(node) < model_.node_bone.size() &&
           model_.node_bone[std::size_t(node)] == bone;
  };
  for (const ContactAnchor& a : s.node_cube)
    if (on(a.point)) return true;
  for (const ContactAnchor& a : s.sample_cube)
    for (const int node : model_.skin_samples[std::size_t(a.point)].nodes)
      if (on(node)) return true;
  return false;
}

void PinchLossWatch::watch_touches(const HandSimState& s) {
  if (thumb_touch_s_ < 0 && touches(s, script_.thumb_bone)) thumb_touch_s_ = s.time;
  if (index_touch_s_ < 0 && touches(s, script_.index_bone)) index_touch_s_ = s.time;
  if (thumb_touch_s_ < 0 || index_touch_s_ < 0) return;
  touch_lead_ms_ = 1000 * (index_touch_s_ - thumb_touch_s_);
  turn_at_touch_deg_ = cube_turn_deg(s);
}

void PinchLossWatch::observe(const HandSimState& s) {
  const double h = model_.parameters.time_step;
  if (!touch_lead_ms_ && s.time < script_.lift_start - 0.5 * h) watch_touches(s);
  if (s.time <= script_.close_end + 0.5 * h) {
    const Eigen::Vector3d moved = s.cube_pose.position - script_.cube_centre;
    pushed_mm_ = std::max(pushed_mm_, 1000 * std::hypot(moved.x(), moved.z()));
  }
  if (!lift_seen_ && s.time >= script_.lift_start - 0.5 * h) {
    grip_at_lift_n_ = grip_force(model_, s);
    lift_seen_ = true;
  }
}

PinchLoss PinchLossWatch::loss(bool held) const {
  if (held) return PinchLoss::kNone;
  if (grip_at_lift_n_ > 0.0) return PinchLoss::kSlippedAtLift;
  return pushed_mm_ > 250 * script_.cube_size ? PinchLoss::kPushedAway : PinchLoss::kSqueezedOut;
}

}  // namespace handlab::sim
