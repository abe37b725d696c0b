#include "studies/participant/motor_primitives.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace handlab::studies {

double minimum_jerk(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}

double fitts_time(double a, double b, double distance, double width) {
  const double id = std::log2(2.0 * std::max(distance, 0.0) / std::max(width, 1e-6));
  return a + b * std::max(id, 1.0);
}

double practice_factor(int repetition, double rate, double floor) {
  return floor + (1.0 - floor) * std::exp(-rate * double(std::max(repetition, 1) - 1));
}

double MotorRandom::normal() {
  return random_.normal();
}

double MotorRandom::truncated_normal(double mean, double sd, double low, double high) {
  for (int k = 0; k < 64; ++k) {
    const double x = normal(mean, sd);
    if (x >= low && x <= high) return x;
  }
  return std::clamp(mean, low, high);
}

double MotorRandom::ex_gaussian(double mu, double sigma, double tau) {
  const double gauss = normal(mu, sigma);
  const double exponential = -tau * std::log(1.0 - random_.uniform());
  return std::max(0.05, gauss + exponential);
}

Eigen::Vector3d MinimumJerkMove::at(double t) const {
  const double u = duration > 0 ? (t - start) / duration : 1.0;
  return from + minimum_jerk(u) * (to - from);
}

}  // namespace handlab::studies
