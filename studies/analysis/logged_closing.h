// A logged grasp's closing in the grasp map's terms (core/task/grasp_closing.h), read on the
// intermediate hand its frames hold (what the soft hand followed), so that the grasps of any
// study, real or simulated, can be placed on the map of `handlab-cli sim grasp`.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"
#include "core/store/frame_record.h"
#include "core/task/finger_pads.h"

namespace handlab::studies {

struct LoggedClosing {
  // m: how far each pad is past its face, on average over the two: half of what the pads' gap
  // along the faces' normal falls short of the side (negative: the gap is wider), the median
  // over the grasp's frames. The faces are the pair the pads were across before either
  // touched, so that pads that close through a small cube count past it, not outside.
  double over_closure = 0.0;
  // rad: the pinch's axis (index pad to thumb pad) from the faces' normal once both digits
  // touch, about the cube's most upright other axis (yaw) and about the third (pitch);
  // magnitudes, the map's levels either side of 0 being near mirror images.
  double tilt_yaw = 0.0, tilt_pitch = 0.0;
  double offset_along = 0.0;  // of the side: the pads' midpoint from the centre along the third
  // s: the index's first touch of the cube minus the thumb's in the contact run that led to
  // the grasp (positive: the thumb first; any part of the digit: a finger resting on the
  // cube's top counts from then); NaN when a digit's touch was not logged.
  double lead_s = 0.0;
  // m/s: the pads' mean speed against the cube over the 0.1 s before each touched.
  double closing_speed = 0.0;
  // m: how deep the skin of the bones but the two distal phalanges lies inside the cube
  // (negative: how far it keeps off), the median over the grasp's frames: a finger across
  // the cube's top pins it to the floor. Not a factor of the map, whose pinch the pinch's rule
  // places again where it is deeper than 2 mm (core/task/pinch_clearance.h).
  double other_skin_depth = 0.0;
};

// LoggedClosing's fields by the grasp map's factor names, in the map's units, and the other
// skin's depth, which is not a factor of the map.
struct LoggedFactor {
  const char* name;  // the map's factor (or other_skin_depth)
  const char* unit;
  double LoggedClosing::*field;
  double scale;  // the unit in SI
};
const std::vector<LoggedFactor>& logged_factors();

// The 10th, 50th and 90th percentiles (type 7) of a factor over closings, in its unit,
// leaving out those where it is NaN; n the closings counted.
struct FactorSpread {
  int n = 0;
  double p10 = 0.0, median = 0.0, p90 = 0.0;
};
FactorSpread factor_spread(const std::vector<LoggedClosing>& closings, const LoggedFactor& f);
// The same of any values (SI), in a unit of `unit` SI (NaN left out).
FactorSpread spread_of(const std::vector<double>& values, double unit);

// Reads closings for one simulated hand: its pads (finger_pads.h) from its flesh, built once.
class ClosingReader {
 public:
  explicit ClosingReader(const hand::HandShape& simulated_hand);
  // The closing of the grasp whose first grasped frame is frames[grasp], on a cube of `side`.
  LoggedClosing read(const std::vector<store::FrameRecord>& frames, std::size_t grasp,
                     double side) const;

 private:
  struct Pads {
    Eigen::Vector3d thumb, index;  // in the cube's frame
  };
  hand::HandPose pose_at(const store::FrameRecord& f) const;  // the intermediate hand
  Pads pads_at(const store::FrameRecord& f) const;

  double other_skin_depth(const store::FrameRecord& f, double side) const;

  hand::Skeleton skeleton_;
  sim::HandSimModel model_;  // the simulated hand's, for the skin each bone carries
  sim::PinchPads pads_;
};

}  // namespace handlab::studies
