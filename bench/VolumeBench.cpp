// Volume costs on the tooth phantom: building it, sampling densities, one
// milling stamp, the point shell and its incremental update.
#include <benchmark/benchmark.h>

#include <random>

#include "millsim/volume/Milling.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeSampler.h"

using namespace millsim;

namespace {

const VoxelVolume& phantom() {
  static const VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  return v;
}

void BM_PhantomBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(makeToothPhantom(ToothPhantomOptions{}).activeVoxels());
}
BENCHMARK(BM_PhantomBuild)->Unit(benchmark::kMillisecond)->Iterations(3);

// Points anywhere in the volume.
void BM_SampleRandom(benchmark::State& state) {
  const auto& v = phantom();
  VolumeSampler s(v);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(0, v.dims().x - 1), uy(0, v.dims().y - 1), uz(0, v.dims().z - 1);
  std::vector<glm::dvec3> pts(4096);
  for (auto& p : pts) p = {ux(rng), uy(rng), uz(rng)};
  for (auto _ : state)
    for (const auto& p : pts) benchmark::DoNotOptimize(s.density(p));
  state.SetItemsProcessed(state.iterations() * std::int64_t(pts.size()));
}
BENCHMARK(BM_SampleRandom);

// Points in a small cluster near the occlusal surface, as a tool's samples are.
std::vector<glm::dvec3> nearSurfacePoints(const VoxelVolume& v) {
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0.0, 10.0);
  const glm::dvec3 c = v.localToIndex({0.0, 8.5e-3, 0.0});
  std::vector<glm::dvec3> pts(4096);
  for (auto& p : pts) p = c + glm::dvec3(n(rng), n(rng), n(rng));
  return pts;
}

void BM_SampleNearSurface(benchmark::State& state) {
  const auto& v = phantom();
  VolumeSampler s(v);
  const std::vector<glm::dvec3> pts = nearSurfacePoints(v);
  for (auto _ : state)
    for (const auto& p : pts) benchmark::DoNotOptimize(s.density(p));
  state.SetItemsProcessed(state.iterations() * std::int64_t(pts.size()));
}
BENCHMARK(BM_SampleNearSurface);

// The same points sampled as VolumeSampler did before its one-leaf fast path:
// eight accessor lookups per trilinear cell. The ratio to BM_SampleNearSurface
// is the fast path's gain.
void BM_SampleNearSurfaceEightLookups(benchmark::State& state) {
  const auto& v = phantom();
  VolumeSampler s(v);
  const std::vector<glm::dvec3> pts = nearSurfacePoints(v);
  for (auto _ : state)
    for (const auto& p : pts) {
      const int i = int(std::floor(p.x)), j = int(std::floor(p.y)), k = int(std::floor(p.z));
      const double tx = p.x - i, ty = p.y - j, tz = p.z - k;
      const float c0 = s.voxel(i, j, k), c1 = s.voxel(i + 1, j, k), c2 = s.voxel(i, j + 1, k),
                  c3 = s.voxel(i + 1, j + 1, k), c4 = s.voxel(i, j, k + 1), c5 = s.voxel(i + 1, j, k + 1),
                  c6 = s.voxel(i, j + 1, k + 1), c7 = s.voxel(i + 1, j + 1, k + 1);
      const double x00 = c0 + (c1 - c0) * tx, x10 = c2 + (c3 - c2) * tx;
      const double x01 = c4 + (c5 - c4) * tx, x11 = c6 + (c7 - c6) * tx;
      const double y0 = x00 + (x10 - x00) * ty, y1 = x01 + (x11 - x01) * ty;
      benchmark::DoNotOptimize(y0 + (y1 - y0) * tz);
    }
  state.SetItemsProcessed(state.iterations() * std::int64_t(pts.size()));
}
BENCHMARK(BM_SampleNearSurfaceEightLookups);

void BM_MillStamp(benchmark::State& state) {
  VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  Miller miller(v, 700.f);
  DirtyBlocks dirty(v.dims());
  double y = 9.5e-3;
  for (auto _ : state) {
    // Drill downwards a little each stamp so every stamp removes material.
    miller.stamp({0.0, y, 0.0}, 0.5e-3, dirty);
    y -= 0.005e-3;
    dirty.clear();
  }
}
BENCHMARK(BM_MillStamp)->Unit(benchmark::kMicrosecond)->Iterations(1000);

void BM_PointShellBuild(benchmark::State& state) {
  const auto& v = phantom();
  std::size_t n = 0;
  for (auto _ : state) n = PointShell(v, 700.f, int(state.range(0))).size();
  state.counters["points"] = double(n);
}
BENCHMARK(BM_PointShellBuild)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

void BM_PointShellUpdateAfterStamp(benchmark::State& state) {
  VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  PointShell shell(v, 700.f, int(state.range(0)));
  Miller miller(v, 700.f);
  DirtyBlocks dirty(v.dims());
  double y = 9.5e-3;
  for (auto _ : state) {
    state.PauseTiming();
    miller.stamp({0.0, y, 0.0}, 0.5e-3, dirty);
    y -= 0.005e-3;
    state.ResumeTiming();
    shell.update(v, dirty.origins());
    dirty.clear();
  }
}
BENCHMARK(BM_PointShellUpdateAfterStamp)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond)->Iterations(500);

}  // namespace
