// Drawing the default lesson offscreen (OSMesa, llvmpipe) at 512×512, with
// VolumeMesh's level of detail (the 2×2×2-averaged mesh where a voxel covers
// under 1.5 pixels) and without it, in one run: issue 15's frame-rate goal is
// ≥ 30 Hz at p95 while milling; this is the frame without the milling's
// re-meshing. Each iteration draws and reads the pixels back (llvmpipe draws
// when asked for them).
#include <benchmark/benchmark.h>

#include <optional>

#include "millsim/core/NodeRegistry.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/x3d/X3DLoader.h"

namespace {

using namespace millsim;

const LoadResult& lesson() {
  static const LoadResult r = loadSceneFile(MILLSIM_SOURCE_DIR "/x3d/default.x3d", builtinRegistry());
  return r;
}

void BM_DrawDefaultLesson(benchmark::State& state) {
  const LoadResult& r = lesson();
  if (!r.ok()) {
    state.SkipWithError("x3d/default.x3d does not load");
    return;
  }
  RendererOptions o;
  o.width = o.height = 512;
  o.levelOfDetail = state.range(0) != 0;
  auto renderer = createSceneRenderer(*r.scene, o);
  for (auto _ : state) {
    renderer->render(std::nullopt);
    benchmark::DoNotOptimize(renderer->readPixels());
  }
  state.SetLabel(o.levelOfDetail ? "level of detail" : "every voxel");
}
BENCHMARK(BM_DrawDefaultLesson)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
