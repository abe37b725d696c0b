// Timing a part of a step's solve (StepTimer, sim_options.h): a scope's wall time added to its
// timer in the step's report. Timing only reads the clock, so the step's result is the same.
#pragma once

#include <chrono>

#include "core/sim/sim_options.h"

namespace handlab::sim {

// Adds the wall time from its construction to stop() or its end, whichever comes first.
class ScopedStepTimer {
 public:
  ScopedStepTimer(SimStepReport& report, StepTimer timer)
      : total_(&report.timer_ms[std::size_t(timer)]), begin_(std::chrono::steady_clock::now()) {}
  ~ScopedStepTimer() { stop(); }
  ScopedStepTimer(const ScopedStepTimer&) = delete;
  ScopedStepTimer& operator=(const ScopedStepTimer&) = delete;
  void stop() {
    if (!total_) return;
    *total_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin_)
                   .count();
    total_ = nullptr;
  }

 private:
  double* total_;
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace handlab::sim
