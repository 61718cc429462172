// Algorithm #3 (BarbicRenderer) per-frame cost on the tooth phantom at the
// paper's point-shell scales 1, 2, 3 (§8.1: 127 / 507 / 987 Hz), on the
// paper's 256×256×176 grid and on an 8×-voxel 512×512×352 one, culled by the
// shell hierarchy and brute force (every point tested) in the same run; and
// the point shell's update after one burr stamp, fast path against the
// block-rebuild path. Counters: p50/p99 frame time, contacts, shell points.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "millsim/run/ThreadCpuTime.h"
#include "millsim/renderers/BarbicRenderer.h"
#include "millsim/renderers/ToolSdf.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

// 0: the paper's grid (0.1 mm); 1: 8× the voxels (0.05 mm).
VoxelVolume& phantom(int which) {
  static std::map<int, std::unique_ptr<VoxelVolume>> cache;
  auto& v = cache[which];
  if (!v)
    v = std::make_unique<VoxelVolume>(makeToothPhantom(
        which == 0 ? ToothPhantomOptions{} : ToothPhantomOptions{{512, 512, 352}, 0.05e-3, false}));
  return *v;
}

const ToolGeometry kTool{0.6e-3, 0.4e-3, 15e-3};  // the lesson's burr

// The burr centre over the central fossa, the shaft leaning 15° and circling once a second.
Pose contactPose(long n, double y) {
  const double a = 2.0 * M_PI * double(n % 1000) / 1000.0;
  return Pose{{0.0, y, 0.0}, glm::angleAxis(0.26, glm::dvec3(std::cos(a), 0.0, std::sin(a)))};
}

double surfaceHeight(const VoxelScene& scene) {
  double y = 12e-3;
  while (y > 0.0 && !scene.inside({0.0, y, 0.0})) y -= 0.01e-3;
  return y;
}

// args: scale, phantom (0/1), culling (1) or brute force (0).
void BM_Barbic(benchmark::State& state) {
  const int scale = int(state.range(0));
  VoxelScene scene;
  scene.addVolume(phantom(int(state.range(1))), glm::dmat4(1.0), 700.0);
  BarbicRenderer r;
  r.pointShellScale.set(scale);
  r.culling.set(state.range(2) != 0);
  // The device 0.3 mm into the enamel: the burr centre this far below where it touches.
  const double y = surfaceHeight(scene) + kTool.tipRadius - 0.3e-3;
  auto algorithm = r.compile(kTool, scene);
  algorithm->reset(Pose{{0.0, 12e-3, 0.0}, glm::dquat(1, 0, 0, 0)});
  for (int i = 0; i <= 100; ++i) algorithm->step(scene, {contactPose(0, 12e-3 + (y - 12e-3) * i / 100.0), 1e-3});
  for (int i = 0; i < 100; ++i) algorithm->step(scene, {contactPose(0, y), 1e-3});
  std::vector<double> us, cpu;
  us.reserve(1 << 16), cpu.reserve(1 << 16);
  long n = 0;
  double contacts = 0;
  int fallbacks = 0;
  for (auto _ : state) {
    const double c0 = threadCpuMicros();
    const auto t0 = std::chrono::steady_clock::now();
    const HapticOutput out = algorithm->step(scene, {contactPose(n++, y), 1e-3});
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = threadCpuMicros();
    benchmark::DoNotOptimize(out.force);
    contacts += out.contacts;
    fallbacks += (out.flags & kFlagCoarseFallback) != 0;
    if (us.size() < us.capacity()) {
      us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      cpu.push_back(c1 - c0);
    }
  }
  std::sort(us.begin(), us.end());
  std::sort(cpu.begin(), cpu.end());
  if (!us.empty()) {
    state.counters["p50_us"] = us[us.size() / 2];
    state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
    state.counters["cpu_p50_us"] = cpu[cpu.size() / 2];
    state.counters["cpu_p99_us"] = cpu[std::min(cpu.size() - 1, cpu.size() * 99 / 100)];
    state.counters["p50_Hz"] = 1e6 / cpu[cpu.size() / 2];
  }
  state.counters["contacts"] = contacts / double(std::max<long>(1, n));
  state.counters["fallbacks"] = fallbacks;
  state.counters["points"] = double(PointShell(phantom(int(state.range(1))), 700.f, scale).size());
}
BENCHMARK(BM_Barbic)
    ->ArgNames({"scale", "fine", "cull"})
    ->ArgsProduct({{1, 2, 3}, {0, 1}, {1, 0}})
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(1000);

// Point-shell update after one stamp of the lesson's burr (0.6 mm) or a 1 mm
// burr, drilling down into the crown. args: scale, burr radius (µm), fast (1) / blocks (0).
void BM_ShellUpdateAfterStamp(benchmark::State& state) {
  VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  const int scale = int(state.range(0));
  const double radius = double(state.range(1)) * 1e-6;
  PointShell shell(v, 700.f, scale);
  Miller miller(v, 700.f);
  DirtyBlocks dirty(v.dims());
  double y = 9.5e-3;
  double buckets = 0;
  std::vector<double> cpu;
  cpu.reserve(4096);
  for (auto _ : state) {
    dirty.clear();
    miller.stamp({0.0, y, 0.0}, radius, dirty);
    y -= 0.01e-3;
    // Manual time = the update's own thread CPU time (no pause/resume overhead, no preemption).
    const double c0 = threadCpuMicros();
    buckets += state.range(2) ? shell.update(v, dirty) : shell.update(v, dirty.origins());
    const double c1 = threadCpuMicros();
    state.SetIterationTime((c1 - c0) * 1e-6);
    cpu.push_back(c1 - c0);
  }
  std::sort(cpu.begin(), cpu.end());
  state.counters["buckets"] = buckets / double(state.iterations());
  state.counters["cpu_p50_us"] = cpu[cpu.size() / 2];
  state.counters["cpu_p99_us"] = cpu[std::min(cpu.size() - 1, cpu.size() * 99 / 100)];
}
BENCHMARK(BM_ShellUpdateAfterStamp)
    ->ArgNames({"scale", "radius_um", "fast"})
    ->ArgsProduct({{1, 2, 3}, {600, 1000}, {1, 0}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(300);

}  // namespace

namespace {

// The tool distance per query: exact analytic form (0) against the sampled
// grid at 0.05 mm (1), on points spread over the tool's box.
void BM_ToolSdf(benchmark::State& state) {
  const ToolSdf sdf(kTool, 0.05e-3);
  std::vector<glm::dvec3> q(4096);
  unsigned seed = 1;
  auto next = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
  for (auto& p : q) p = sdf.boxLo() + (sdf.boxHi() - sdf.boxLo()) * glm::dvec3(next(), next(), next());
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    const glm::dvec3& p = q[i++ & 4095];
    sum += state.range(0) ? sdf.sampledDistance(p) : sdf.distance(p);
  }
  benchmark::DoNotOptimize(sum);
}
BENCHMARK(BM_ToolSdf)->ArgName("sampled")->Arg(0)->Arg(1);

}  // namespace
