// Frame logging as the session runner does it: what the simulation thread pays per 120 Hz
// frame (encode + queue) while the writer thread commits batches to a real study database.
#include <chrono>
#include <filesystem>

#include <benchmark/benchmark.h>

#include "core/store/frame_logger.h"
#include "core/store/study_store.h"
#include "core/tracking/recording_io.h"

namespace handlab {
namespace {

store::FrameRecord study_frame() {
  store::FrameRecord f;
  const auto recording =
      tracking::read_recording(std::string(HANDLAB_SOURCE_DIR) + "/data/leap/pinch.json.lz");
  for (const auto& frame : recording.frames)
    if (!frame.hands.empty()) {
      f.tracked = frame;  // one hand with its bone bases, as the Leap service sends it
      break;
    }
  f.angles.assign(21, 0.1f);
  f.bone_positions.assign(16, Eigen::Vector3f(0.1f, 0.2f, 0.3f));
  f.bone_rotations.assign(16, Eigen::Quaternionf::Identity());
  return f;
}

void BM_FrameEncode(benchmark::State& state) {
  const store::FrameRecord frame = study_frame();
  std::vector<std::uint8_t> blob;
  for (auto _ : state) {
    store::encode_frame(frame, blob);
    benchmark::DoNotOptimize(blob.data());
  }
  state.counters["bytes"] = double(blob.size());
}
BENCHMARK(BM_FrameEncode);

void BM_FrameLog(benchmark::State& state) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "handlab_bench_frames.db").string();
  for (const char* side : {"", "-wal", "-shm"}) std::filesystem::remove(path + side);
  store::StudyDefinition d;
  d.name = "bench";
  d.protocol_text = "{}";
  d.factors = {"f"};
  d.conditions = {{"a", {"a"}}};
  store::StudyStore::create(path, d);
  store::StudyStore db(path);
  store::Participant p;
  p.id = "B";
  p.age = 30;
  p.sex = "X";
  p.handedness = "right";
  p.hand_length = 0.18;
  p.vr_experience = "none";
  store::PlannedTrialRow row;
  row.order = 1;
  db.add_participant(p, {row});
  const std::int64_t trial = db.begin_trial(db.next_trial("B")->id, db.begin_session("B", "bench"));

  store::FrameRecord frame = study_frame();
  std::int64_t seq = 0;
  {
    store::FrameLogger logger(path);
    for (auto _ : state) {
      frame.time = double(seq) / 120.0;
      logger.log(trial, seq++, frame);
    }
    const auto start = std::chrono::steady_clock::now();
    logger.flush();
    state.counters["flush_ms"] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["frames"] = double(seq);
  for (const char* side : {"", "-wal", "-shm"}) std::filesystem::remove(path + side);
}
// A 5-minute session's worth of frames at 120 Hz per run.
BENCHMARK(BM_FrameLog)->Iterations(36000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace handlab
