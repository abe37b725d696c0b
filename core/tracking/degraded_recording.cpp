#include "core/tracking/degraded_recording.h"

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>

#include "core/tracking/frame_source.h"

namespace handlab::tracking {
namespace {

std::vector<TrackedFrame> resampled(const std::vector<TrackedFrame>& frames, double rate_hz) {
  ReplayOptions options;
  options.pace = ReplayPace::kResampled;
  options.rate_hz = rate_hz;
  options.sleep = [](double) {};
  RecordingReplay replay(frames, options);
  std::vector<TrackedFrame> out;
  while (auto frame = replay.next()) out.push_back(std::move(*frame));
  return out;
}

// A jump under way: its angle and the frames it has left.
struct Jump {
  double angle = 0.0;
  int frames_left = 0;
};

// Turns digit d's joints past its knuckle (the Leap's pip, dip and tip) about the knuckle (its
// mcp).
void turn_finger(TrackedHand& hand, std::size_t d, double angle) {
  const Eigen::Vector3d axis = palm_frame(hand).col(0);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  const Eigen::Vector3d knuckle = hand.joints[d][1];
  for (std::size_t k = 2; k < 5; ++k)
    hand.joints[d][k] = knuckle + r * (hand.joints[d][k] - knuckle);
}

}  // namespace

std::vector<TrackedFrame> degrade(const std::vector<TrackedFrame>& frames,
                                  const Degradation& degradation) {
  const Degradation& g = degradation;
  if (!(g.joint_noise >= 0) || !(g.jump_chance >= 0 && g.jump_chance <= 1) || g.jump_frames < 1 ||
      !(g.rate_hz >= 0) || !(g.max_jump_angle >= 0))
    throw std::invalid_argument(
        "degrade: noise and rate >= 0, a jump's chance in [0, 1], its angle >= 0 and frames >= 1");
  std::vector<TrackedFrame> out = g.rate_hz > 0 ? resampled(frames, g.rate_hz) : frames;
  std::mt19937_64 random(g.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::map<std::pair<std::int32_t, std::size_t>, Jump> jumps;  // by hand id and finger
  for (TrackedFrame& frame : out)
    for (TrackedHand& hand : frame.hands) {
      for (std::size_t d = 0; d < 5; ++d) {
        Jump& jump = jumps[{hand.id, d}];
        if (jump.frames_left == 0 && g.jump_chance > 0 && unit(random) < g.jump_chance)
          jump = {g.max_jump_angle * (2.0 * unit(random) - 1.0), g.jump_frames};
        if (jump.frames_left > 0) {
          turn_finger(hand, d, jump.angle);
          --jump.frames_left;
        }
      }
      if (g.joint_noise > 0) {
        auto jitter = [&](Eigen::Vector3d& p) {
          for (int i = 0; i < 3; ++i) p[i] += g.joint_noise * noise(random);
        };
        jitter(hand.palm_position);
        jitter(hand.wrist);
        for (auto& digit : hand.joints)
          for (Eigen::Vector3d& joint : digit) jitter(joint);
      }
    }
  return out;
}

}  // namespace handlab::tracking
