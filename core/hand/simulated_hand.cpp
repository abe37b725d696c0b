#include "core/hand/simulated_hand.h"

#include <cmath>

#include "core/hand/degrees.h"

namespace handlab::hand {

Skeleton build_simulated_hand(const HandShape& shape) {
  const double hl = shape.length, hb = shape.hand_breadth();
  const double side = shape.left ? -1.0 : 1.0;  // mirrors x
  const Eigen::Vector3d x_axis(1, 0, 0), z_axis(0, 0, 1);
  Skeleton s;

  Bone palm;
  palm.name = "palm";
  palm.length = 0.446 * hl;
  palm.radius = 0.3 * shape.palm_thickness * hl;
  s.bones.push_back(palm);

  // Finger rest directions spread slightly (open hand): angles about +z, radial positive.
  const double splay_deg[kFingerCount] = {0.0, 6.0, 0.0, -7.0, -16.0};
  // Joint limits (degrees) from range-of-motion studies; see docs/hand-model.md.
  struct Limits {
    double mcp_flex[2], mcp_abd[2], pip[2], dip[2];
  };
  const Limits finger_limits = {{-30, 90}, {-20, 20}, {0, 110}, {-10, 85}};

  for (int f = 0; f < kFingerCount; ++f) {
    const FingerProportions& p = shape.fingers[std::size_t(f)];
    const std::string name = finger_name(f);
    const double width = p.width * hl * shape.tissue;
    Eigen::Vector3d base(side * p.base_across * hb, p.base_along * hl, 0.0);
    std::array<double, 3> lengths;
    Eigen::Matrix3d rest;
    if (f == 0) {
      // The thumb's metacarpal leaves the CMC radially, distally and palmarly; its frame is
      // turned about the bone (pronated) so that flexion carries the thumb across the palm.
      base.z() = 0.18 * shape.palm_thickness * hl;
      rest = frame_along(Eigen::Vector3d(0.74, 0.66, 0.12), Eigen::Vector3d(-0.2, 0.1, 1.0));
      // A left hand is the mirror image M R M (M = diag(-1, 1, 1)) of the right hand's frame.
      const Eigen::Matrix3d mirror = Eigen::Vector3d(side, 1, 1).asDiagonal();
      rest = mirror * rest * mirror;
      lengths = {p.metacarpal * hl, p.proximal * hl, p.distal * hl};
    } else {
      rest = axis_rotation(-side * z_axis, splay_deg[f] * kDeg);  // about -z is radial
      lengths = {p.proximal * hl, p.middle * hl, p.distal * hl};
    }
    int parent = 0;
    for (int segment = 0; segment < 3; ++segment) {
      Bone bone;
      bone.name = name + std::to_string(segment + 1);
      bone.parent = parent;
      bone.length = lengths[std::size_t(segment)];
      bone.radius = 0.22 * width * (1.0 - 0.08 * segment);
      if (segment == 0) {
        bone.offset = base;
        bone.rest = rest;
      } else {
        bone.offset = Eigen::Vector3d(0, lengths[std::size_t(segment - 1)], 0);
      }
      // Flexion about +x carries +y towards +z (palmar) in both hands; rotation about -z
      // carries it radially (+x). Mirroring turns a rotation about a into one about -M a, so
      // the abduction (z) and axial (y) axes flip for the left hand while flexion keeps +x;
      // positive abduction is always radial.
      const Eigen::Vector3d flex = x_axis;
      if (f == 0) {
        if (segment == 0) {
          add_dof(s, bone, name + "_cmc_flexion", flex, -20, 55);
          add_dof(s, bone, name + "_cmc_abduction", -side * z_axis, -25, 45);
          add_dof(s, bone, name + "_cmc_rotation", Eigen::Vector3d(0, side, 0), -25, 55);
        } else if (segment == 1) {
          add_dof(s, bone, name + "_mcp_flexion", flex, -40, 70);
        } else {
          add_dof(s, bone, name + "_ip_flexion", flex, -45, 85);
        }
      } else if (segment == 0) {
        add_dof(s, bone, name + "_mcp_flexion", flex, finger_limits.mcp_flex[0],
                finger_limits.mcp_flex[1]);
        add_dof(s, bone, name + "_mcp_abduction", -side * z_axis, finger_limits.mcp_abd[0],
                finger_limits.mcp_abd[1]);
      } else if (segment == 1) {
        add_dof(s, bone, name + "_pip_flexion", flex, finger_limits.pip[0], finger_limits.pip[1]);
      } else {
        add_dof(s, bone, name + "_dip_flexion", flex, finger_limits.dip[0], finger_limits.dip[1]);
      }
      s.bones.push_back(bone);
      parent = int(s.bones.size()) - 1;
    }
    const int first = int(s.bones.size()) - 3;
    const char* joints_finger[3] = {"_mcp", "_pip", "_dip"};
    const char* joints_thumb[3] = {"_cmc", "_mcp", "_ip"};
    for (int segment = 0; segment < 3; ++segment)
      s.markers.push_back({name + (f == 0 ? joints_thumb : joints_finger)[segment], first + segment,
                           Eigen::Vector3d::Zero()});
    s.markers.push_back({name + "_tip", first + 2, Eigen::Vector3d(0, lengths[2], 0)});
  }
  return s;
}

std::array<int, kFingerCount> fingertip_markers(const Skeleton& skeleton) {
  std::array<int, kFingerCount> tips;
  for (int f = 0; f < kFingerCount; ++f)
    tips[std::size_t(f)] = skeleton.marker_index(std::string(finger_name(f)) + "_tip");
  return tips;
}

}  // namespace handlab::hand
