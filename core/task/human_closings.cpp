#include "core/task/human_closings.h"

#include <algorithm>
#include <cmath>

#include "core/util/portable_random.h"

namespace handlab::sim {
namespace {

constexpr double kDegree = M_PI / 180.0;

double log_normal(util::PortableRandom& random, double median, double sigma) {
  return median * std::exp(sigma * random.normal());
}

double clipped_normal(util::PortableRandom& random, double sd, double limit) {
  return std::clamp(sd * random.normal(), -limit, limit);
}

}  // namespace

const std::vector<ClosingParameter>& human_closing_parameters() {
  static const std::vector<ClosingParameter> table = {
      {"over_closure",
       "log-normal, both pads alike, median 6 mm, 90 % within 1.8-20 mm, at most 30 mm",
       "Prachyabrued & Borst 2012 (Int J Hum-Comput Stud 70(11)), 2014 (IEEE 3DUI) and 2016 "
       "(IEEE TVCG 22(6)) measured the real fingers' penetration of virtual objects grasped "
       "without haptics (30 people picking up and dropping a ball); their depths were not at "
       "hand",
       true},
      {"tilt_yaw", "normal, mean 0, SD 5 deg, within 30 deg",
       "Kleinholdermann, Brenner, Franz & Smeets 2007 (Exp Brain Res 180:415): the digits reach "
       "faces about at right angles; Cuijpers, Brenner & Smeets 2008: grip orientation follows a "
       "virtual cylinder's with gain 0.42 without matching haptics (a gain, not a spread)",
       true},
      {"tilt_pitch", "normal, mean 0, SD 5 deg, within 30 deg", "as tilt_yaw", true},
      {"offset_along", "normal, mean 0, SD 3 mm (0.1 of the side at most), within 0.4 of the side",
       "Lederman & Wing 2003 (Exp Brain Res 152:156): precision grips of planar objects land "
       "'just a few millimetres' from the centre of mass",
       true},
      {"lead", "normal, mean 0, SD 25 ms, within 80 ms",
       "Schettino et al. 2013 (Exp Brain Res 227:477) report which digit touches first, not "
       "the delay",
       true},
      {"closing_speed",
       "log-normal, both pads alike, median 4 cm/s, 90 % within 1.3-12 cm/s, from "
       "2 to 30 cm/s",
       "Smeets & Brenner 1999 (Motor Control 3:237): the digits approach the faces slowly and "
       "at right angles; no speed at contact at hand",
       true},
      {"lift_acceleration", "0.6 m/s2, the scripted pinch's lift (10 cm in 1 s): not drawn",
       "none: how briskly people lift a light object after a precision grip was not measured "
       "here; the grid maps it alone and in pairs",
       true},
      {"hold", "5 s, the scripted pinch's",
       "a lab lift's hold (Johansson & Westling 1988 held 10 s); a pick-and-place holds "
       "shorter",
       true},
      {"jitter", "1: the recording's own (sim grasp --jitter-from)",
       "a real recording's tracker jitter (data/leap: Leap Motion, LeapJS Playback): the "
       "intermediate hand retargeted from it by Naive less its 0.1 s moving average",
       false},
  };
  return table;
}

std::vector<ClosingPoint> human_closing_draws(int count, std::uint64_t seed, double cube_size,
                                              double jitter) {
  util::PortableRandom random(seed);
  std::vector<ClosingPoint> points;
  for (int i = 0; i < count; ++i) {
    GraspClosing c;
    c.over_closure = std::min(log_normal(random, 0.006, 0.73), 0.030);
    c.tilt_yaw = clipped_normal(random, 5 * kDegree, 30 * kDegree);
    c.tilt_pitch = clipped_normal(random, 5 * kDegree, 30 * kDegree);
    c.offset_along = clipped_normal(random, std::min(0.003 / cube_size, 0.1), 0.4);
    c.lead_s = clipped_normal(random, 0.025, 0.080);
    c.closing_speed = std::clamp(log_normal(random, 0.04, 0.67), 0.02, 0.30);
    c.jitter = jitter;
    c.jitter_phase = random.uniform();  // each draw its own stretch of the recording
    points.push_back({"draw", double(i + 1), c});
  }
  return points;
}

}  // namespace handlab::sim
