// Reading LeapJS Playback recordings (.json.lz): LZ-string decompression, JSON parsing,
// checks and conversion to tracked frames.
#include <benchmark/benchmark.h>

#include "core/tracking/recording_io.h"

namespace {

void BM_ReadRecording(benchmark::State& state, const char* file) {
  const std::string path = std::string(HANDLAB_SOURCE_DIR) + "/data/leap/" + file;
  std::size_t frames = 0, hands = 0;
  for (auto _ : state) {
    const auto r = handlab::tracking::read_recording(path);
    frames = r.frames.size();
    hands = 0;
    for (const auto& f : r.frames) hands += f.hands.size();
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(double(frames), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hands_per_s"] =
      benchmark::Counter(double(hands), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_CAPTURE(BM_ReadRecording, pinch, "pinch.json.lz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadRecording, pinch_57fps_packed, "pinch-57fps.json.lz")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadRecording, grab, "grab.json.lz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadRecording, wave, "wave.json.lz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadRecording, confidence2_two_hands, "confidence2.json.lz")
    ->Unit(benchmark::kMillisecond);

}  // namespace
