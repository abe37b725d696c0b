// What the simulator's steps cost over a run (a trial, a session, a study): how many steps,
// how many of them factorised the Newton matrix, their passes, CG iterations, wall-clock time
// and its parts (StepTimer). Counting only: where a simulated study's time goes
// (docs/performance.md).
#pragma once

#include <array>
#include <cstddef>

#include "core/sim/sim_options.h"

namespace handlab::sim {

struct StepTotals {
  long steps = 0;
  long factorizing_steps = 0;  // steps with at least one factorisation
  long factorizations = 0;
  long passes = 0;  // Newton iterations: a step takes more than one when contacts changed
  long linear_iterations = 0, direct_solves = 0, halvings = 0;
  double seconds = 0.0;                             // wall clock inside HandSimulator::step
  std::array<double, kStepTimers> timer_seconds{};  // the parts of it (SimStepReport::timer_ms)

  void add(const SimStepReport& r, double step_seconds) {
    ++steps;
    factorizing_steps += r.factorizations > 0 ? 1 : 0;
    factorizations += r.factorizations;
    passes += r.newton_iterations;
    linear_iterations += r.linear_iterations;
    direct_solves += r.direct_solves;
    halvings += r.halvings;
    seconds += step_seconds;
    for (std::size_t k = 0; k < kStepTimers; ++k) timer_seconds[k] += 1e-3 * r.timer_ms[k];
  }
  StepTotals& operator+=(const StepTotals& o) {
    steps += o.steps;
    factorizing_steps += o.factorizing_steps;
    factorizations += o.factorizations;
    passes += o.passes;
    linear_iterations += o.linear_iterations;
    direct_solves += o.direct_solves;
    halvings += o.halvings;
    seconds += o.seconds;
    for (std::size_t k = 0; k < kStepTimers; ++k) timer_seconds[k] += o.timer_seconds[k];
    return *this;
  }
};

}  // namespace handlab::sim
