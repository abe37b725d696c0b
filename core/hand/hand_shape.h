// Measurable shape parameters of a hand, with anthropometric defaults.
#pragma once

#include <array>
#include <string>

namespace handlab::hand {

enum class Finger { kThumb = 0, kIndex, kMiddle, kRing, kPinky };
constexpr int kFingerCount = 5;
const char* finger_name(int finger);  // "thumb", "index", "middle", "ring", "pinky"

// Segment lengths as fractions of hand length, and joint positions, after Buchholz,
// Armstrong & Goldstein (1992), Ergonomics 35(3):261-273, Table 2 and Figure 3.
struct FingerProportions {
  double metacarpal, proximal, middle, distal;  // fractions of HL (thumb: middle = 0)
  double base_along;   // MCP (thumb: CMC) distance from the wrist crease along HL, fraction of HL
  double base_across;  // MCP (thumb: CMC) offset across the hand, fraction of HB (+ radial)
  double width;        // finger breadth at the proximal phalanx, fraction of HL
};

struct HandShape {
  double length = 0.214;          // HL: wrist crease to the tip of the middle finger (m)
  double breadth = 0.0;           // HB: across the MCPs (m); 0 means 0.45 HL
  double palm_thickness = 0.125;  // fraction of HL, dorsal to palmar skin at mid-palm
  double tissue = 1.0;            // scales every finger's breadth and thickness
  std::array<FingerProportions, kFingerCount> fingers = default_proportions();
  bool left = false;  // mirror across the hand's long axis

  double hand_breadth() const { return breadth > 0 ? breadth : 0.45 * length; }
  static std::array<FingerProportions, kFingerCount> default_proportions();
  // A hand of the given length with the default proportions.
  static HandShape with_length(double hand_length);
};

}  // namespace handlab::hand
