// Drawing the default lesson offscreen (OSMesa, llvmpipe) at 512×512, with
// VolumeMesh's level of detail (the 2×2×2-averaged mesh where a voxel covers
// under 1.5 pixels) and without it, in one run: issue 15's frame-rate goal is
// ≥ 30 Hz at p95 while milling; this is the frame without the milling's
// re-meshing. Each iteration draws and reads the pixels back (llvmpipe draws
// when asked for them). Then what capping a cut costs (issue 47, part 7).
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/graphics/CutSection.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/volume/VoxelVolume.h"
#include "millsim/x3d/X3DLoader.h"

namespace {

using namespace millsim;

const LoadResult& lesson() {
  static const LoadResult r = loadSceneFile(MILLSIM_SOURCE_DIR "/x3d/default.x3d", builtinRegistry());
  return r;
}

// Draws `r`'s scene at 512², with the level of detail when the argument is 1.
// The first draw, which meshes the level it draws (VolumeMesh), is not timed.
void timeDraws(benchmark::State& state, const LoadResult& r, const char* what) {
  if (!r.ok()) {
    state.SkipWithError((std::string(what) + " does not load").c_str());
    return;
  }
  RendererOptions o;
  o.width = o.height = 512;
  o.levelOfDetail = state.range(0) != 0;
  auto renderer = createSceneRenderer(*r.scene, o);
  renderer->render(std::nullopt);
  for (auto _ : state) {
    renderer->render(std::nullopt);
    benchmark::DoNotOptimize(renderer->readPixels());
  }
  state.counters["triangles"] = double(renderer->stats().triangles);
  state.SetLabel(o.levelOfDetail ? "level of detail" : "every voxel");
}

void BM_DrawDefaultLesson(benchmark::State& state) { timeDraws(state, lesson(), "x3d/default.x3d"); }
BENCHMARK(BM_DrawDefaultLesson)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The same lesson at micro-CT voxels (25 µm, the phantom 1024 × 1024 × 704),
// with and without the level of detail, in one run: seen whole at 512² a
// voxel covers a quarter of a pixel, and the 8³-averaged level is drawn
// (issue 44, part 4: ≥ 30 Hz p95 while milling).
void BM_DrawLessonAtMicroCtVoxels(benchmark::State& state) {
  static const LoadResult r = [] {
    std::ifstream in(MILLSIM_SOURCE_DIR "/x3d/default.x3d");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string what : {"phantom:tooth-labels", "phantom:tooth"}) {
      const std::string quoted = "\"" + what + "\"";
      if (const std::size_t at = text.find(quoted); at != std::string::npos)
        text.replace(at, quoted.size(), "\"" + what + "?size=1024,1024,704&amp;voxel=0.000025\"");
    }
    return loadSceneString(text, MILLSIM_SOURCE_DIR "/x3d/default.x3d", builtinRegistry(), {}, MILLSIM_SOURCE_DIR "/x3d");
  }();
  timeDraws(state, r, "x3d/default.x3d at 25 um");
}
BENCHMARK(BM_DrawLessonAtMicroCtVoxels)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The cut-plane lesson with its cut capped by the section and open, in one
// run: what a cap costs a frame when neither the plane nor the tooth moves
// (its texture is sampled once, at the first draw).
void BM_DrawCutLesson(benchmark::State& state) {
  static const LoadResult r = loadSceneFile(MILLSIM_SOURCE_DIR "/x3d/lessons/cut-plane.x3d", builtinRegistry());
  if (!r.ok()) {
    state.SkipWithError("x3d/lessons/cut-plane.x3d does not load");
    return;
  }
  RendererOptions o;
  o.width = o.height = 512;
  o.capCuts = state.range(0) != 0;
  auto renderer = createSceneRenderer(*r.scene, o);
  renderer->render(std::nullopt);  // meshes the tooth (VolumeMesh) and samples the cap once: not timed
  for (auto _ : state) {
    renderer->render(std::nullopt);
    benchmark::DoNotOptimize(renderer->readPixels());
  }
  state.SetLabel(o.capCuts ? "capped" : "open");
}
BENCHMARK(BM_DrawCutLesson)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// Sampling a cap: the whole section of the paper-resolution phantom through
// its middle (a moved plane), and the part one milling stamp on the plane
// re-samples (a frame of milling where the cut is).
const SceneView& cutTooth() {
  static const LoadResult r = loadSceneFile(MILLSIM_SOURCE_DIR "/x3d/lessons/cut-plane.x3d", builtinRegistry());
  static const SceneView view = readSceneView(*r.scene);
  return view;
}

void BM_CutSectionWhole(benchmark::State& state) {
  const DrawVolume& dv = cutTooth().volumes.at(0);
  CutSection section(*dv.voxels, float(dv.iso), dv.tissues);
  double offset = 0.0;
  for (auto _ : state) {
    offset = offset == 0.0 ? 1e-6 : 0.0;  // a plane moved by a micrometre: sampled afresh
    benchmark::DoNotOptimize(section.aim(glm::dvec4(0.0, 0.0, -1.0, offset), dv.localToWorld));
  }
  state.counters["texels"] = double(section.width() * section.height());
}
BENCHMARK(BM_CutSectionWhole)->Unit(benchmark::kMillisecond);

void BM_CutSectionStamp(benchmark::State& state) {
  const DrawVolume& dv = cutTooth().volumes.at(0);
  CutSection section(*dv.voxels, float(dv.iso), dv.tissues);
  section.aim(glm::dvec4(0.0, 0.0, -1.0, 0.0), dv.localToWorld);
  // The blocks a 0.6 mm burr on the plane at the crown's top touches (3 × 3 × 3 blocks of 8³ around it).
  const glm::ivec3 centre(glm::round(dv.voxels->localToIndex(glm::dvec3(0.0, 8.0e-3, 0.0))));
  std::vector<BlockOrigin> blocks;
  for (int k = -1; k <= 1; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) blocks.push_back((centre / 8 + glm::ivec3(i, j, k)) * 8);
  const std::uint64_t before = section.texelsSampled();
  for (auto _ : state) benchmark::DoNotOptimize(section.update(blocks));
  state.counters["texels"] = double(section.texelsSampled() - before) / double(state.iterations());
}
BENCHMARK(BM_CutSectionStamp)->Unit(benchmark::kMicrosecond);

}  // namespace
