// Volume costs on the tooth phantom: building it, reading it back from a
// file, sampling densities, one milling stamp, the point shell and its
// incremental update; and voxelising a surface mesh (MeshVolume).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include <glm/geometric.hpp>

#include "millsim/volume/BlockChannel.h"
#include "millsim/volume/MeshVolume.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeIO.h"
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

// Reading the phantom back from a NRRD (arg 0: raw, 1: gzip), streamed into
// the sparse grid a slab at a time (VolumeBuilder): voxels of the box per second.
void BM_ReadNrrd(benchmark::State& state) {
  const bool gzip = state.range(0) != 0;
  const auto file = std::filesystem::temp_directory_path() / (gzip ? "millsim-bench-gzip.nrrd" : "millsim-bench-raw.nrrd");
  writeNrrd(phantom(), file, gzip);
  for (auto _ : state) benchmark::DoNotOptimize(readNrrd(file, phantom().airValue()).activeVoxels());
  const glm::ivec3 d = phantom().dims();
  state.SetItemsProcessed(state.iterations() * std::int64_t(d.x) * d.y * d.z);
  std::filesystem::remove(file);
}
BENCHMARK(BM_ReadNrrd)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A sphere of 5 mm radius, an icosahedron subdivided `levels` times (20·4^levels triangles).
SurfaceMesh icosphere(int levels) {
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  MeshPart p{"ball", {}, {}};
  for (glm::vec3 v : {glm::vec3(-1, t, 0), {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t}, {0, -1, -t},
                      {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    p.vertices.push_back(glm::normalize(v));
  p.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6},
                 {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10},
                 {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto middle = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      p.vertices.push_back(glm::normalize(p.vertices[a] + p.vertices[b]));
      return mid[key] = unsigned(p.vertices.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& f : p.triangles) {
      const unsigned ab = middle(f.x, f.y), bc = middle(f.y, f.z), ca = middle(f.z, f.x);
      next.insert(next.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
    }
    p.triangles = std::move(next);
  }
  for (glm::vec3& v : p.vertices) v *= 5.f;
  return SurfaceMesh{"generated", {std::move(p)}};
}

// Voxelising a closed mesh (open-edge check, OpenVDB's meshToVolume, the
// densities and labels): arg 0 the subdivision (6: 82 k triangles, 8: 1.3 M),
// arg 1 the voxel in µm. Triangles per second is the figure to quote.
void BM_VoxeliseMesh(benchmark::State& state) {
  const SurfaceMesh mesh = icosphere(int(state.range(0)));
  MeshVoxelOptions o;
  o.voxelSize = double(state.range(1)) * 1e-6;
  o.unit = 1e-3;
  std::size_t voxels = 0;
  for (auto _ : state) voxels = voxeliseMesh(mesh, "ball", o).density.activeVoxels();
  state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.triangleCount()));
  state.counters["triangles"] = double(mesh.triangleCount());
  state.counters["voxels"] = double(voxels);
}
BENCHMARK(BM_VoxeliseMesh)->Args({6, 50})->Args({8, 50})->Args({8, 25})->Unit(benchmark::kMillisecond)->Iterations(2);

// Times `sample(sampler, p)` over the points, as samples per second. Pass
// lambdas (kTrilinear, kEightLookups): a function pointer would not be inlined.
template <class Sample> void samplePoints(benchmark::State& state, const std::vector<glm::dvec3>& pts, Sample sample) {
  VolumeSampler s(phantom());
  for (auto _ : state)
    for (const auto& p : pts) benchmark::DoNotOptimize(sample(s, p));
  state.SetItemsProcessed(state.iterations() * std::int64_t(pts.size()));
}
constexpr auto kTrilinear = [](const VolumeSampler& s, const glm::dvec3& p) { return s.density(p); };

// Points anywhere in the volume.
void BM_SampleRandom(benchmark::State& state) {
  const auto& v = phantom();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(0, v.dims().x - 1), uy(0, v.dims().y - 1), uz(0, v.dims().z - 1);
  std::vector<glm::dvec3> pts(4096);
  for (auto& p : pts) p = {ux(rng), uy(rng), uz(rng)};
  samplePoints(state, pts, kTrilinear);
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

void BM_SampleNearSurface(benchmark::State& state) { samplePoints(state, nearSurfacePoints(phantom()), kTrilinear); }
BENCHMARK(BM_SampleNearSurface);

// A trilinear sample as VolumeSampler took it before its leaf fast paths:
// eight accessor lookups per cell.
double eightLookups(const VolumeSampler& s, const glm::dvec3& p) {
  const int i = int(std::floor(p.x)), j = int(std::floor(p.y)), k = int(std::floor(p.z));
  const double tx = p.x - i, ty = p.y - j, tz = p.z - k;
  const float c0 = s.voxel(i, j, k), c1 = s.voxel(i + 1, j, k), c2 = s.voxel(i, j + 1, k),
              c3 = s.voxel(i + 1, j + 1, k), c4 = s.voxel(i, j, k + 1), c5 = s.voxel(i + 1, j, k + 1),
              c6 = s.voxel(i, j + 1, k + 1), c7 = s.voxel(i + 1, j + 1, k + 1);
  const double x00 = c0 + (c1 - c0) * tx, x10 = c2 + (c3 - c2) * tx;
  const double x01 = c4 + (c5 - c4) * tx, x11 = c6 + (c7 - c6) * tx;
  const double y0 = x00 + (x10 - x00) * ty, y1 = x01 + (x11 - x01) * ty;
  return y0 + (y1 - y0) * tz;
}

constexpr auto kEightLookups = [](const VolumeSampler& s, const glm::dvec3& p) { return eightLookups(s, p); };

// The same points sampled with eight lookups: the ratio to
// BM_SampleNearSurface is the fast paths' gain.
void BM_SampleNearSurfaceEightLookups(benchmark::State& state) {
  samplePoints(state, nearSurfacePoints(phantom()), kEightLookups);
}
BENCHMARK(BM_SampleNearSurfaceEightLookups);

// Near-surface points moved into cells that straddle a leaf boundary along
// one axis (a third of all cells straddle one or more): VolumeSampler probes
// each leaf once there; against eight lookups.
std::vector<glm::dvec3> straddlingPoints(const VoxelVolume& v) {
  std::vector<glm::dvec3> pts = nearSurfacePoints(v);
  for (std::size_t n = 0; n < pts.size(); ++n) {
    double& x = n % 3 == 0 ? pts[n].x : n % 3 == 1 ? pts[n].y : pts[n].z;
    x = 8.0 * std::floor(x / 8.0) + 7.0 + (x - std::floor(x));
  }
  return pts;
}
void BM_SampleStraddling(benchmark::State& state) { samplePoints(state, straddlingPoints(phantom()), kTrilinear); }
BENCHMARK(BM_SampleStraddling);
void BM_SampleStraddlingEightLookups(benchmark::State& state) {
  samplePoints(state, straddlingPoints(phantom()), kEightLookups);
}
BENCHMARK(BM_SampleStraddlingEightLookups);

// A milled block published to graphics (BlockChannel::tryPush, on the
// haptic thread in every milling frame): its 512 values copied from the
// leaf's buffer, one block near the occlusal surface.
BlockOrigin occlusalBlock(const VoxelVolume& v) {
  const glm::dvec3 c = v.localToIndex({0.0, 8.5e-3, 0.0});
  return {int(c.x) & ~7, int(c.y) & ~7, int(c.z) & ~7};
}

void BM_PublishBlock(benchmark::State& state) {
  const auto& v = phantom();
  const BlockOrigin o = occlusalBlock(v);
  if (!v.grid().tree().probeConstLeaf(openvdb::Coord(o.x, o.y, o.z))) state.SkipWithError("no leaf at the block");
  BlockChannel channel(1);
  for (auto _ : state) {
    channel.tryPush(v, o);
    channel.drain([](const BlockUpdate& u) { benchmark::DoNotOptimize(u.values[511]); });
  }
}
BENCHMARK(BM_PublishBlock);

// The same copy through getValue per voxel, as tryPush did until Dec 2026:
// the ratio to BM_PublishBlock is the direct read's gain.
void BM_PublishBlockPerVoxelGetValue(benchmark::State& state) {
  const auto& v = phantom();
  const BlockOrigin o = occlusalBlock(v);
  const auto* leaf = v.grid().tree().probeConstLeaf(openvdb::Coord(o.x, o.y, o.z));
  if (!leaf) state.SkipWithError("no leaf at the block");
  std::array<float, 512> values{};
  for (auto _ : state) {
    if (!leaf) break;
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          values[std::size_t((z * 8 + y) * 8 + x)] = leaf->getValue(openvdb::Coord(x + o.x, y + o.y, z + o.z));
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_PublishBlockPerVoxelGetValue);

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
