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

void PinchLossWatch::observe(const HandSimState& s) {
  const double h = model_.parameters.time_step;
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
