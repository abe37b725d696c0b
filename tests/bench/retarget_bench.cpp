// Retargeting one tracked frame onto the study hand, warm-started as in a session: every
// frame of pinch.json.lz in turn.
#include <benchmark/benchmark.h>

#include "core/hand/simulated_hand.h"
#include "core/retarget/retargeter.h"
#include "core/tracking/recording_io.h"

namespace {

void BM_RetargetFrame(benchmark::State& state) {
  using namespace handlab;
  const auto recording =
      tracking::read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz");
  const hand::Skeleton simulated = hand::build_simulated_hand(hand::HandShape::with_length(0.214));
  auto fitter =
      tracking::TrackedHandFitter::for_recording(recording.frames, tracking::Side::kRight);
  const auto calibration =
      retarget::calibrate_open_palm(recording.frames, tracking::Side::kRight, simulated, *fitter);
  const auto strategy =
      state.range(0) == 0 ? retarget::Strategy::kOurs : retarget::Strategy::kNaive;
  retarget::Retargeter retargeter(strategy, simulated, *calibration, fitter);
  std::vector<const tracking::TrackedHand*> hands;
  for (const auto& f : recording.frames)
    if (const auto* h = f.hand(tracking::Side::kRight)) hands.push_back(h);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(retargeter.retarget(*hands[i]).iterations);
    if (++i == hands.size()) i = 0;
  }
}
BENCHMARK(BM_RetargetFrame)->Arg(0)->Arg(1)->ArgName("naive")->Unit(benchmark::kMicrosecond);

}  // namespace
