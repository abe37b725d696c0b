// One simulation frame as the study database keeps it: the tracker's frame exactly as it
// arrived (handlab's tracked-frame encoding, doubles bit for bit), then the intermediate
// pose, the simulated bones and the cube as little-endian float32s behind a small header
// (about 1.2 kB at the study size), cheap to encode on the simulation thread.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "core/tracking/tracked_frame.h"

namespace handlab::store {

struct FrameRecord {
  double time = 0.0;               // s since the trial started
  tracking::TrackedFrame tracked;  // as the tracker delivered it (no hands: none seen)
  // Intermediate hand (scene frame).
  Eigen::Vector3f root_position = Eigen::Vector3f::Zero();
  Eigen::Quaternionf root_rotation = Eigen::Quaternionf::Identity();
  std::vector<float> angles;  // per DOF (rad)
  // Simulated bones (scene frame).
  std::vector<Eigen::Vector3f> bone_positions;
  std::vector<Eigen::Quaternionf> bone_rotations;
  // Cube.
  Eigen::Vector3f cube_position = Eigen::Vector3f::Zero();
  Eigen::Quaternionf cube_rotation = Eigen::Quaternionf::Identity();
  std::uint8_t task_phase = 0;
  bool thumb_contact = false, index_contact = false;
};

// Appends the encoding to `out` (cleared first; its capacity is reused).
void encode_frame(const FrameRecord& frame, std::vector<std::uint8_t>& out);
// Throws std::runtime_error on a blob that is not a frame of this encoding.
FrameRecord decode_frame(std::span<const std::uint8_t> blob);

}  // namespace handlab::store
