#include "core/tracking/frame_source.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <Eigen/Geometry>

namespace handlab::tracking {
namespace {

Eigen::Matrix3d slerp(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double s) {
  // Leap's matrices are printed to six digits, so they are only nearly orthonormal: the
  // quaternions are normalised so that the result is a rotation.
  const Eigen::Quaterniond qa = Eigen::Quaterniond(a).normalized(),
                           qb = Eigen::Quaterniond(b).normalized();
  return qa.slerp(s, qb).toRotationMatrix();
}

// The palm's frame from its normal and direction, and back.

TrackedHand blend(const TrackedHand& a, const TrackedHand& b, double s) {
  TrackedHand h = a;
  auto lerp = [s](const Eigen::Vector3d& p, const Eigen::Vector3d& q) -> Eigen::Vector3d {
    return p + s * (q - p);
  };
  h.confidence = a.confidence + s * (b.confidence - a.confidence);
  h.pinch_strength = a.pinch_strength + s * (b.pinch_strength - a.pinch_strength);
  h.grab_strength = a.grab_strength + s * (b.grab_strength - a.grab_strength);
  h.palm_position = lerp(a.palm_position, b.palm_position);
  h.wrist = lerp(a.wrist, b.wrist);
  const Eigen::Matrix3d r = slerp(palm_frame(a), palm_frame(b), s);
  h.direction = r.col(1);
  h.palm_normal = r.col(2);
  for (std::size_t d = 0; d < 5; ++d)
    for (std::size_t k = 0; k < 5; ++k) h.joints[d][k] = lerp(a.joints[d][k], b.joints[d][k]);
  if (a.bone_bases && b.bone_bases) {
    for (std::size_t d = 0; d < 5; ++d)
      for (std::size_t k = 0; k < 4; ++k) {
        // Leap bases may be left-handed (left hands); slerp their rotation part.
        const Eigen::Matrix3d& ma = (*a.bone_bases)[d][k];
        const Eigen::Matrix3d& mb = (*b.bone_bases)[d][k];
        const double sign = ma.determinant() < 0 ? -1.0 : 1.0;
        Eigen::Matrix3d ra = ma, rb = mb;
        ra.col(0) *= sign;
        rb.col(0) *= sign;
        Eigen::Matrix3d m = slerp(ra, rb, s);
        m.col(0) *= sign;
        (*h.bone_bases)[d][k] = m;
      }
  } else {
    h.bone_bases.reset();
  }
  h.derived = a.derived | b.derived;
  return h;
}

}  // namespace

TrackedFrame interpolate(const TrackedFrame& a, const TrackedFrame& b, double t) {
  const double span = b.timestamp - a.timestamp;
  const double s = span > 0 ? std::clamp((t - a.timestamp) / span, 0.0, 1.0) : 0.0;
  TrackedFrame out;
  out.timestamp = t;
  out.id = s < 0.5 ? a.id : b.id;
  const TrackedFrame& nearer = s < 0.5 ? a : b;
  const TrackedFrame& farther = s < 0.5 ? b : a;
  for (const TrackedHand& h : nearer.hands) {
    const TrackedHand* other = nullptr;
    for (const TrackedHand& g : farther.hands)
      if (g.id == h.id && g.side == h.side) other = &g;
    if (!other) {
      out.hands.push_back(h);
    } else if (&nearer == &a) {
      out.hands.push_back(blend(h, *other, s));
    } else {
      out.hands.push_back(blend(*other, h, s));
    }
  }
  return out;
}

RecordingReplay::RecordingReplay(std::vector<TrackedFrame> frames, ReplayOptions options)
    : frames_(std::move(frames)), options_(std::move(options)) {
  if (options_.pace == ReplayPace::kResampled &&
      !(options_.rate_hz > 0 && std::isfinite(options_.rate_hz)))
    throw std::invalid_argument("resampling needs a positive rate");
  if (!options_.sleep)
    options_.sleep = [](double seconds) {
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    };
  if (!frames_.empty()) time_ = frames_.front().timestamp;
}

std::optional<TrackedFrame> RecordingReplay::next() {
  if (frames_.empty()) return std::nullopt;
  switch (options_.pace) {
    case ReplayPace::kAsFastAsPossible:
      if (index_ >= frames_.size()) return std::nullopt;
      return frames_[index_++];
    case ReplayPace::kRealTime: {
      if (index_ >= frames_.size()) return std::nullopt;
      if (index_ > 0) options_.sleep(frames_[index_].timestamp - frames_[index_ - 1].timestamp);
      return frames_[index_++];
    }
    case ReplayPace::kResampled: {
      if (time_ > frames_.back().timestamp + 1e-12) return std::nullopt;
      while (index_ + 1 < frames_.size() && frames_[index_ + 1].timestamp < time_) ++index_;
      const TrackedFrame& a = frames_[index_];
      const TrackedFrame& b = frames_[std::min(index_ + 1, frames_.size() - 1)];
      TrackedFrame out = interpolate(a, b, time_);
      time_ += 1.0 / options_.rate_hz;
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace handlab::tracking
