// Independent runs side by side: each index of [0, count) run once, `jobs` threads taking the
// next one as they finish (long simulations of uneven length: the grasp map, real pinches).
#pragma once

#include <cstddef>
#include <functional>

namespace handlab::util {

// Runs `run(i)` for every i in [0, count) on max(1, jobs) threads. `done`, if given, is called
// with the count finished after each run, under a lock, from the thread that finished it. The
// first exception thrown by a run is rethrown once all threads have stopped.
void run_in_parallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& run,
                     const std::function<void(int done)>& done = {});

}  // namespace handlab::util
