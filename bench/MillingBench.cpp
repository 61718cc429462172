// One milling frame of Algorithm #3 (BarbicRenderer) on the tooth phantom:
// the burr stamp, the dirty-block tracking and the point-shell update, as
// VoxelScene::mill does them with the shells Barbic registers (its shell at
// pointShellScale s and the coarse fallback at 2s). Next to it, in the same
// run, the same frame with a full rebuild of the shell instead of the
// incremental update; the rebuild variant reports the ratio to the
// incremental one (x_incremental). The burr drills a 2.5 mm hole the way the
// §8.2 procedure does: circling 0.4 mm off the axis while it sinks.
// Counters: thread-CPU p50 / p99 / max per frame (µs), the stamp's own p50 /
// p99, points, the fraction of stamps that removed material.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include <unistd.h>

#include "millsim/run/ThreadCpuTime.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

constexpr double kBurr = 0.6e-3;  // the lesson's burr radius
constexpr double kTop = 9.9e-3;   // just above the occlusal surface over the fossa

// Frame n's burr centre: one turn per 400 frames, sinking 2.5 mm over 4000 frames.
glm::dvec3 burrAt(long n) {
  const double a = 2.0 * M_PI * double(n % 400) / 400.0;
  return {0.4e-3 * std::cos(a), kTop - 2.5e-3 * double(n % 4000) / 4000.0, 0.4e-3 * std::sin(a)};
}

std::map<int, double>& incrementalP50() {
  static std::map<int, double> p50;  // by scale, for the rebuild variant's ratio
  return p50;
}

// The phantom at `micrometres` voxels (100: the paper's 256 x 256 x 176).
ToothPhantomOptions phantomAt(long micrometres) {
  ToothPhantomOptions o;
  o.dims = o.dims * int(100 / micrometres);
  o.voxelSize = double(micrometres) * 1e-6;
  return o;
}

// args: scale, full rebuild (1) or incremental update (0), voxel size (µm: 100, 50 or 25),
// the volume's millingBudget (densities read a frame; 0: no limit).
void BM_MillingFrame(benchmark::State& state) {
  const int scale = int(state.range(0));
  const bool rebuild = state.range(1) != 0;
  VoxelVolume volume = makeToothPhantom(phantomAt(state.range(2)));
  VoxelScene scene;
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  scene.volume(0).millingBudget = long(state.range(3));
  // What BarbicRenderer's compile() registers.
  PointShell& fine = const_cast<PointShell&>(scene.shell(0, scale));
  scene.pointShell(0, 2 * scale);
  std::vector<double> cpu, stampCpu;
  cpu.reserve(1 << 14), stampCpu.reserve(1 << 14);
  long n = 0, cutting = 0;
  for (auto _ : state) {
    const glm::dvec3 c = burrAt(n++);
    const double c0 = threadCpuMicros();
    double removed;
    if (rebuild) {
      removed = scene.mill(c, kBurr);
      fine.rebuildAll(volume);
    } else {
      removed = scene.mill(c, kBurr);
      stampCpu.push_back(threadCpuMicros() - c0);
      // The shell as the next step sees it (a lazy scene merges the stamp here).
      benchmark::DoNotOptimize(scene.pointShell(0, scale).size());
    }
    const double c1 = threadCpuMicros();
    state.SetIterationTime((c1 - c0) * 1e-6);
    cutting += removed > 0.0;
    if (cpu.size() < cpu.capacity()) cpu.push_back(c1 - c0);
  }
  std::sort(cpu.begin(), cpu.end());
  const double p50 = cpu[cpu.size() / 2];
  state.counters["cpu_p50_us"] = p50;
  state.counters["cpu_p99_us"] = cpu[std::min(cpu.size() - 1, cpu.size() * 99 / 100)];
  state.counters["cpu_max_us"] = cpu.back();
  if (!stampCpu.empty()) {  // the stamp and its dirty-block tracking alone
    std::sort(stampCpu.begin(), stampCpu.end());
    state.counters["stamp_p50_us"] = stampCpu[stampCpu.size() / 2];
    state.counters["stamp_p99_us"] = stampCpu[std::min(stampCpu.size() - 1, stampCpu.size() * 99 / 100)];
  }
  state.counters["cutting"] = double(cutting) / double(std::max<long>(1, n));
  state.counters["points"] = double(scene.pointShell(0, scale).size());
  const int key = scale * 1000 + int(state.range(2));
  if (state.range(3) != 0) return;  // a budget's frame is not the rebuild's baseline
  if (!rebuild) incrementalP50()[key] = p50;
  else if (incrementalP50().count(key)) state.counters["x_incremental"] = p50 / incrementalP50()[key];
}
// Each scale's incremental run first (the rebuild run divides by its p50);
// a full rebuild takes milliseconds, so it runs fewer frames.
BENCHMARK(BM_MillingFrame)->Args({1, 0, 100, 0})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({1, 1, 100, 0})->Iterations(20)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({2, 0, 100, 0})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({2, 1, 100, 0})->Iterations(20)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({3, 0, 100, 0})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({3, 1, 100, 0})->Iterations(20)->UseManualTime()->Unit(benchmark::kMicrosecond);
// Micro-CT resolution (issue 44): the same hole at 50 and 25 µm voxels.
BENCHMARK(BM_MillingFrame)->Args({1, 0, 50, 0})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({1, 0, 25, 0})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
// Paced: the same frames with VolumeObject.millingBudget at 2000 and 1000 densities a frame.
BENCHMARK(BM_MillingFrame)->Args({1, 0, 50, 2000})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({1, 0, 25, 2000})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MillingFrame)->Args({1, 0, 25, 1000})->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);

// The stamp alone (Miller::stamp and its dirty-block marks), without the
// scene's sampler window and shells: the same hole at 100, 50 and 25 µm.
// Counters: thread-CPU p50 / p99 / max (µs), voxels changed a stamp (p50),
// densities read a stamp (p50, p99: the unit of VolumeObject.millingBudget).
void BM_Stamp(benchmark::State& state) {
  VoxelVolume volume = makeToothPhantom(phantomAt(state.range(0)));
  Miller miller(volume, 700.f);
  DirtyBlocks dirty(volume.dims());
  std::vector<double> cpu, changed, read;
  cpu.reserve(4000), changed.reserve(4000), read.reserve(4000);
  long n = 0;
  for (auto _ : state) {
    dirty.clear();
    const double c0 = threadCpuMicros();
    const StampResult r = miller.stamp(burrAt(n++), kBurr, dirty);
    const double c1 = threadCpuMicros();
    state.SetIterationTime((c1 - c0) * 1e-6);
    if (cpu.size() < cpu.capacity())
      cpu.push_back(c1 - c0), changed.push_back(r.voxelsChanged), read.push_back(double(r.voxelsRead));
  }
  std::sort(cpu.begin(), cpu.end());
  std::sort(changed.begin(), changed.end());
  std::sort(read.begin(), read.end());
  state.counters["cpu_p50_us"] = cpu[cpu.size() / 2];
  state.counters["read_p50"] = read[read.size() / 2];
  state.counters["read_p99"] = read[std::min(read.size() - 1, read.size() * 99 / 100)];
  state.counters["cpu_p99_us"] = cpu[std::min(cpu.size() - 1, cpu.size() * 99 / 100)];
  state.counters["cpu_max_us"] = cpu.back();
  state.counters["changed_p50"] = changed[changed.size() / 2];
}
BENCHMARK(BM_Stamp)->ArgName("um")->Arg(100)->Arg(50)->Arg(25)->Iterations(4000)->UseManualTime()->Unit(benchmark::kMicrosecond);

// The price of a dormant shell: Barbic's coarse fallback (scale 2s) or a
// renderer waiting in a RendererPool merges, when it is next asked for,
// everything milled since. args: scale of the dormant shell, frames milled
// while it slept (the burr path above). Manual time: the catch-up alone.
void BM_DormantCatchUp(benchmark::State& state) {
  const int scale = int(state.range(0));
  const long frames = long(state.range(1));
  for (auto _ : state) {
    VoxelVolume volume = makeToothPhantom(ToothPhantomOptions{});
    VoxelScene scene;
    scene.addVolume(volume, glm::dmat4(1.0), 700.0);
    scene.pointShell(0, scale);
    for (long n = 0; n < frames; ++n) scene.mill(burrAt(n), kBurr);
    const double c0 = threadCpuMicros();
    benchmark::DoNotOptimize(scene.pointShell(0, scale).size());
    state.SetIterationTime((threadCpuMicros() - c0) * 1e-6);
  }
}
BENCHMARK(BM_DormantCatchUp)
    ->ArgNames({"scale", "frames"})
    ->ArgsProduct({{2, 6}, {300, 1000, 4000}})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// The point shell's memory at scale s on the tooth phantom: bytes per point
// by the structure's own accounting (PointShell::memoryBytes: every buffer
// it holds, headroom for milling included) and by the process's resident set
// (/proc/self/statm) before and after building it. Then the 2.5 mm hole of
// BM_MillingFrame (4000 frames): the points it adds.
long residentBytes() {
  long pages = 0, resident = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * sysconf(_SC_PAGESIZE);
}

void BM_PointShellMemory(benchmark::State& state) {
  const int scale = int(state.range(0));
  VoxelVolume volume = makeToothPhantom(ToothPhantomOptions{});
  for (auto _ : state) {
    const long before = residentBytes();
    PointShell shell(volume, 700.f, scale);
    const long after = residentBytes();
    const double n = double(shell.size());
    state.counters["points"] = n;
    state.counters["bytes_per_point"] = double(shell.memoryBytes()) / n;
    state.counters["rss_per_point"] = double(after - before) / n;
    Miller miller(volume, 700.f);
    DirtyBlocks dirty(volume.dims());
    for (long f = 0; f < 4000; ++f) {
      miller.stamp(burrAt(f), kBurr, dirty);
      shell.update(volume, dirty);
      dirty.clear();
    }
    state.counters["hole_adds_points"] = double(shell.size()) - n;
    state.counters["rss_per_point_after_hole"] = double(residentBytes() - before) / n;
  }
}
BENCHMARK(BM_PointShellMemory)->Arg(1)->Arg(3)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
