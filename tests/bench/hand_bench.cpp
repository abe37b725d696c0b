// Generating the study hand: skeleton, skin, TetGen flesh, coupling points, embedded render
// surface.
#include <benchmark/benchmark.h>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/hand/tracked_hand.h"

namespace {

void BM_StudyHandGeneration(benchmark::State& state) {
  using namespace handlab::hand;
  const HandShape shape = HandShape::with_length(0.214);
  FleshOptions options;
  options.resolution = int(state.range(0));
  std::size_t tets = 0;
  for (auto _ : state) {
    const Skeleton skeleton = build_simulated_hand(shape);
    const HandFlesh flesh = build_flesh(skeleton, shape, options);
    tets = flesh.tets.tets.size();
    benchmark::DoNotOptimize(flesh.coupling.data());
  }
  state.counters["tets"] = double(tets);
}
BENCHMARK(BM_StudyHandGeneration)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMillisecond);

void BM_TrackedFrameFit(benchmark::State& state) {
  using namespace handlab::hand;
  const Skeleton tracked = build_tracked_hand(HandShape::with_length(0.18));
  HandPose pose = HandPose::rest(tracked);
  for (Eigen::Index k = 0; k < pose.angles.size(); ++k) pose.angles(k) = 0.2 + 0.01 * double(k);
  const LeapJoints frame = to_leap_joints(tracked, pose);
  for (auto _ : state) benchmark::DoNotOptimize(fit_leap_joints(tracked, frame).rms_residual);
}
BENCHMARK(BM_TrackedFrameFit)->Unit(benchmark::kMicrosecond);

}  // namespace
