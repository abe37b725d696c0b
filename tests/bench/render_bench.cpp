#include <benchmark/benchmark.h>

#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"

namespace {

// One offscreen frame of the task scene at 800x600 (OSMesa, software rasteriser).
void BM_OffscreenSceneFrame(benchmark::State& state) {
  using namespace handlab;
  render::OffscreenRenderer renderer(800, 600, int(state.range(0)));
  const task::SceneLayout layout;
  const render::OrbitCamera camera;
  const render::DrawList list = render::draw_task_scene(layout, task::cube_start_pose(layout));
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(list, camera));
}
BENCHMARK(BM_OffscreenSceneFrame)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

}  // namespace
