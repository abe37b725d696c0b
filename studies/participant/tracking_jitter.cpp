#include "studies/participant/tracking_jitter.h"

#include <algorithm>
#include <cmath>

namespace handlab::studies {

TrackingJitter measure_tracking_jitter(const std::vector<tracking::TrackedFrame>& frames) {
  TrackingJitter result;
  std::vector<double> intervals;
  for (std::size_t k = 1; k < frames.size(); ++k)
    if (frames[k].timestamp > frames[k - 1].timestamp)
      intervals.push_back(frames[k].timestamp - frames[k - 1].timestamp);
  if (intervals.empty()) return result;
  std::nth_element(intervals.begin(), intervals.begin() + long(intervals.size() / 2),
                   intervals.end());
  const double interval = intervals[intervals.size() / 2];
  result.rate_hz = 1.0 / interval;

  // One hand of the same id in three consecutive frames, evenly spaced.
  auto same_hand = [](const tracking::TrackedFrame& f, const tracking::TrackedHand& h) {
    for (const auto& other : f.hands)
      if (other.id == h.id && other.side == h.side) return &other;
    return static_cast<const tracking::TrackedHand*>(nullptr);
  };
  std::vector<double> differences;
  for (std::size_t k = 1; k + 1 < frames.size(); ++k) {
    const double before = frames[k].timestamp - frames[k - 1].timestamp;
    const double after = frames[k + 1].timestamp - frames[k].timestamp;
    if (before <= 0 || after <= 0 || before > 1.5 * interval || after > 1.5 * interval) continue;
    for (const auto& h : frames[k].hands) {
      const auto* a = same_hand(frames[k - 1], h);
      const auto* c = same_hand(frames[k + 1], h);
      if (!a || !c) continue;
      for (int d = 0; d < 5; ++d)
        for (int j = 1; j < 5; ++j) {  // carp is derived in most recordings: left out
          const Eigen::Vector3d second = a->joints[std::size_t(d)][std::size_t(j)] -
                                         2 * h.joints[std::size_t(d)][std::size_t(j)] +
                                         c->joints[std::size_t(d)][std::size_t(j)];
          for (int i = 0; i < 3; ++i) differences.push_back(std::abs(second[i]));
        }
    }
  }
  result.samples = long(differences.size());
  if (differences.empty()) return result;
  std::nth_element(differences.begin(), differences.begin() + long(differences.size() / 2),
                   differences.end());
  result.sd = 1.4826 * differences[differences.size() / 2] / std::sqrt(6.0);
  return result;
}

}  // namespace handlab::studies
