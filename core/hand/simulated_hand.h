// The simulated hand's skeleton, MANO-like: a palm (root) and three bones per finger, 16
// bones, with anatomical rotational DOFs about fixed local axes. Frame: origin at the wrist
// crease, +x radial (towards the thumb of a right hand), +y distal, +z palmar.
#pragma once

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"

namespace handlab::hand {

// Bones: palm, then thumb1..3, index1..3, middle1..3, ring1..3, pinky1..3.
// DOFs per finger: mcp_flexion, mcp_abduction, pip_flexion, dip_flexion; thumb:
// cmc_flexion, cmc_abduction, cmc_rotation, mcp_flexion, ip_flexion (21 in all).
// Markers: "<finger>_tip" at each fingertip, and each joint centre ("index_pip", ...).
Skeleton build_simulated_hand(const HandShape& shape);

// The five fingertip markers' indices, thumb first.
std::array<int, kFingerCount> fingertip_markers(const Skeleton& skeleton);

}  // namespace handlab::hand
