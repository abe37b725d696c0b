#include "core/tracking/hand_fitting.h"

#include <algorithm>

namespace handlab::tracking {

std::optional<double> estimate_hand_length(const std::vector<TrackedFrame>& frames, Side side) {
  std::vector<double> lengths;
  for (const auto& f : frames)
    if (const TrackedHand* h = f.hand(side)) {
      const auto& m = h->joints[2];
      lengths.push_back(((m[2] - m[1]).norm() + (m[3] - m[2]).norm() + (m[4] - m[3]).norm()) /
                        0.544);
    }
  if (lengths.empty()) return std::nullopt;
  std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2),
                   lengths.end());
  return lengths[lengths.size() / 2];
}

hand::LeapJoints leap_joints(const TrackedHand& h) {
  hand::LeapJoints j;
  for (int d = 0; d < 5; ++d) j.joints[std::size_t(d)] = h.joints[std::size_t(d)];
  j.palm_position = h.palm_position;
  j.palm_normal = h.palm_normal;
  j.direction = h.direction;
  j.wrist = h.wrist;
  return j;
}

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

std::optional<hand::MeasuredSkeleton> measure_skeleton(const std::vector<TrackedFrame>& frames,
                                                       Side side, double hand_length) {
  // The wrist frame as the fit sees it: the palm frame moved back by the palm centre offset.
  hand::HandShape shape = hand::HandShape::with_length(hand_length);
  const Eigen::Vector3d palm_offset = hand::palm_centre_offset(shape);
  std::array<std::array<std::vector<double>, 3>, 5> lengths;
  std::array<std::array<std::vector<double>, 3>, 5> mcp, carp;
  bool have_carp = false;
  for (const auto& f : frames) {
    const TrackedHand* h = f.hand(side);
    if (!h) continue;
    const Eigen::Matrix3d r = palm_frame(*h);
    const Eigen::Vector3d root = h->palm_position - r * palm_offset;
    for (int d = 0; d < 5; ++d) {
      const auto& j = h->joints[std::size_t(d)];
      for (int k = 0; k < 3; ++k)
        lengths[std::size_t(d)][std::size_t(k)].push_back(
            (j[std::size_t(k + 2)] - j[std::size_t(k + 1)]).norm());
      const Eigen::Vector3d m = r.transpose() * (j[1] - root), c = r.transpose() * (j[0] - root);
      for (int k = 0; k < 3; ++k) {
        mcp[std::size_t(d)][std::size_t(k)].push_back(m[k]);
        carp[std::size_t(d)][std::size_t(k)].push_back(c[k]);
      }
    }
    have_carp |= !(h->derived & kDerivedCarp);
  }
  if (lengths[0][0].empty()) return std::nullopt;
  // Without measured carps, keep the anthropometric ones.
  const hand::Skeleton reference = hand::build_tracked_hand(shape);
  const hand::LeapJoints rest = hand::to_leap_joints(reference, hand::HandPose::rest(reference));
  hand::MeasuredSkeleton m;
  for (int d = 0; d < 5; ++d) {
    for (int k = 0; k < 3; ++k) {
      m.lengths[std::size_t(d)][std::size_t(k)] = median(lengths[std::size_t(d)][std::size_t(k)]);
      m.mcp[std::size_t(d)][k] = median(mcp[std::size_t(d)][std::size_t(k)]);
      m.carp[std::size_t(d)][k] = have_carp ? median(carp[std::size_t(d)][std::size_t(k)]) : 0.0;
    }
    if (!have_carp)
      m.carp[std::size_t(d)] =
          m.mcp[std::size_t(d)] + (rest.joints[std::size_t(d)][0] - rest.joints[std::size_t(d)][1]);
  }
  return m;
}

TrackedHand tracked_hand(const hand::LeapJoints& j, Side side, std::int32_t id) {
  TrackedHand h;
  h.id = id;
  h.side = side;
  for (int d = 0; d < 5; ++d) h.joints[std::size_t(d)] = j.joints[std::size_t(d)];
  h.palm_position = j.palm_position;
  h.palm_normal = j.palm_normal;
  h.direction = j.direction;
  h.wrist = j.wrist;
  return h;
}

namespace {
hand::Skeleton tracked_skeleton(double hand_length, Side side,
                                const hand::MeasuredSkeleton* measured) {
  hand::HandShape shape = hand::HandShape::with_length(hand_length);
  shape.left = side == Side::kLeft;
  return hand::build_tracked_hand(shape, measured);
}
}  // namespace

TrackedHandFitter::TrackedHandFitter(double hand_length, Side side,
                                     const hand::MeasuredSkeleton* measured)
    : skeleton_(tracked_skeleton(hand_length, side, measured)), workspace_(skeleton_) {}

std::optional<TrackedHandFitter> TrackedHandFitter::for_recording(
    const std::vector<TrackedFrame>& frames, Side side) {
  const auto length = estimate_hand_length(frames, side);
  if (!length) return std::nullopt;
  const auto measured = measure_skeleton(frames, side, *length);
  return TrackedHandFitter(*length, side, &*measured);
}

hand::FitResult TrackedHandFitter::fit(const TrackedHand& h) {
  hand::FitOptions options;
  // Positions the source did not have (derived carps) do not take part.
  if (h.derived & kDerivedCarp)
    for (int d = 0; d < 5; ++d) options.weights[std::size_t(5 * d)] = 0.0;
  if (previous_) options.initial = &*previous_;
  hand::FitResult result = hand::fit_leap_joints(skeleton_, leap_joints(h), options, workspace_);
  previous_ = result.pose;
  return result;
}

}  // namespace handlab::tracking
