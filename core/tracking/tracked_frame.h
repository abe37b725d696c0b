// One frame of a hand tracker: zero, one or two hands, each with its palm frame and the
// joint positions of every digit. SI units (metres, seconds) in the tracker's frame.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace handlab::tracking {

enum class Side : std::uint8_t { kLeft = 0, kRight = 1 };

enum DerivedField : std::uint8_t {
  kDerivedCarp = 1,   // carp positions were not in the source; see docs/tracking.md
  kDerivedWrist = 2,  // the wrist was not in the source
};

struct TrackedHand {
  std::int32_t id = 0;
  Side side = Side::kRight;
  double confidence = 1.0;
  double pinch_strength = 0.0;
  double grab_strength = 0.0;
  Eigen::Vector3d palm_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d palm_normal = -Eigen::Vector3d::UnitY();
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();
  // joints[digit][k]: digits thumb..pinky; k = 0 carp, 1 mcp, 2 pip, 3 dip, 4 tip.
  std::array<std::array<Eigen::Vector3d, 5>, 5> joints{};
  // Bone orientations (columns: x, y, z basis) for metacarpal..distal, when the source has them.
  std::optional<std::array<std::array<Eigen::Matrix3d, 4>, 5>> bone_bases;
  std::uint8_t derived = 0;  // DerivedField flags
};

struct TrackedFrame {
  double timestamp = 0.0;  // s
  std::int64_t id = 0;
  std::vector<TrackedHand> hands;

  const TrackedHand* hand(Side side) const;
};

// The palm's orientation: +y along the direction, +z along the normal (made orthogonal to
// it), +x = y x z (radial for a right hand).
Eigen::Matrix3d palm_frame(const TrackedHand& hand);

// Thumb-index tip distance of a hand (m).
double thumb_index_distance(const TrackedHand& hand);

}  // namespace handlab::tracking
