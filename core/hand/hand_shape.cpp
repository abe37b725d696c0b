#include "core/hand/hand_shape.h"

namespace handlab::hand {

const char* finger_name(int finger) {
  static const char* names[kFingerCount] = {"thumb", "index", "middle", "ring", "pinky"};
  return names[finger];
}

std::array<FingerProportions, kFingerCount> HandShape::default_proportions() {
  // Lengths: Buchholz et al. 1992, Table 2 (segment length / HL). Base positions: their
  // Figure 3 (MCP and CMC locations / HL and / HB). Widths: proximal phalanx breadth / HL
  // from Greiner (1991) US Army hand anthropometry means (about 0.10 HL for the index).
  return {{
      {0.251, 0.196, 0.0, 0.158, 0.073, 0.196, 0.108},     // thumb: CMC
      {0.374, 0.245, 0.143, 0.097, 0.447, 0.251, 0.096},   // index
      {0.373, 0.266, 0.170, 0.108, 0.446, 0.0, 0.098},     // middle
      {0.336, 0.244, 0.165, 0.107, 0.409, -0.206, 0.092},  // ring
      {0.295, 0.204, 0.117, 0.093, 0.368, -0.402, 0.082},  // pinky
  }};
}

HandShape HandShape::with_length(double hand_length) {
  HandShape shape;
  shape.length = hand_length;
  return shape;
}

}  // namespace handlab::hand
