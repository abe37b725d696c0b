// What a simulated participant sees: the display of one frame, nothing more. The
// participant model's only input is this type, so it cannot branch on the condition, its
// label, the strategy, the intermediate hand or anything of the retargeting: none of them
// has a field here (docs/simulated-participants.md; tested by SimulatedParticipantBlinding).
#pragma once

#include <vector>

#include <Eigen/Geometry>

namespace handlab::studies {

// The simulated hand's visible shape: what the drawn hand shows of its bones.
struct SeenHandGeometry {
  std::vector<double> bone_length, bone_radius;  // m, per bone of the simulated hand
  int thumb_distal = -1, index_distal = -1;      // the bones whose pads pinch
};

struct Observation {
  double time = 0.0;                     // s since the trial started
  std::vector<Eigen::Isometry3d> bones;  // simulated hand, world poses; empty: no hand shown
  bool thumb_touching = false, index_touching = false;      // the drawn flesh on the cube
  Eigen::Vector3d cube_position = Eigen::Vector3d::Zero();  // centre (m), floor at y = 0
  Eigen::Quaterniond cube_orientation = Eigen::Quaterniond::Identity();
  double cube_size = 0.0;  // m
  Eigen::Vector3d zone_a = Eigen::Vector3d::Zero(), zone_b = Eigen::Vector3d::Zero();
  double zone_size = 0.0;  // m
};

}  // namespace handlab::studies
