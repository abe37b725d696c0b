#include "core/tracking/tracked_frame.h"

namespace handlab::tracking {

const TrackedHand* TrackedFrame::hand(Side side) const {
  for (const auto& h : hands)
    if (h.side == side) return &h;
  return nullptr;
}

double thumb_index_distance(const TrackedHand& hand) {
  return (hand.joints[0][4] - hand.joints[1][4]).norm();
}

}  // namespace handlab::tracking
