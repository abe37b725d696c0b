// The timing and noise of human movement the simulated participant is built from: minimum-
// jerk profiles, Fitts' law, the ex-Gaussian reaction time, normal draws, and the law of
// practice. Sources in docs/simulated-participants.md.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "core/util/portable_random.h"

namespace handlab::studies {

// Minimum-jerk position fraction at u in [0, 1] (Flash & Hogan 1985): 10u^3 - 15u^4 + 6u^5.
double minimum_jerk(double u);

// Fitts' movement time a + b log2(2 D / W) (s); an index of difficulty under 1 bit counts 1.
double fitts_time(double a, double b, double distance, double width);

// The exponential law of practice of one person (Heathcote, Brown & Mewhort 2000: it fits
// individual learning series better than the power law, which averaging over people makes):
// a duration's factor at its `repetition`-th time, floor + (1 - floor) exp(-rate (n - 1)),
// 1 the first time and falling towards `floor`.
double practice_factor(int repetition, double rate, double floor);

// Draws from one seeded stream.
class MotorRandom {
 public:
  explicit MotorRandom(std::uint64_t seed) : random_(seed) {}
  double uniform() { return random_.uniform(); }
  double normal();  // standard normal (Box-Muller, portable)
  double normal(double mean, double sd) { return mean + sd * normal(); }
  // Normal, redrawn until inside [low, high] (at most 64 draws, then clamped).
  double truncated_normal(double mean, double sd, double low, double high);
  double ex_gaussian(double mu, double sigma, double tau);  // normal + exponential (s)
  Eigen::Vector3d normal3(double sd) { return Eigen::Vector3d(normal(), normal(), normal()) * sd; }

 private:
  util::PortableRandom random_;
};

// A movement of one point from `from` to `to` over `duration`, minimum-jerk.
struct MinimumJerkMove {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
  double start = 0.0, duration = 1.0;
  Eigen::Vector3d at(double t) const;
  bool done(double t) const { return t >= start + duration; }
};

}  // namespace handlab::studies
