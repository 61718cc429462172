// Per-frame cost of the haptics renderers on the tooth phantom during a
// scripted contact — the burr pressed into the occlusal surface with the shaft
// leaning and circling — at the paper's §8.1 resolutions. Reports p50/p99 of
// the frame time as counters, next to Google Benchmark's mean.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "millsim/renderers/LineProxyRenderer.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

VoxelVolume& phantom() {
  static VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  return v;
}

const ToolGeometry kTool{0.6e-3, 0.4e-3, 15e-3};

// Frame n of the scripted contact: the burr centre at height y over the
// central fossa, the shaft leaning 15° and circling once a second.
Pose contactPose(long n, double y) {
  const double a = 2.0 * M_PI * double(n % 1000) / 1000.0;
  const glm::dvec3 axis(std::cos(a), 0.0, std::sin(a));
  return Pose{{0.0, y, 0.0}, glm::angleAxis(0.26, axis)};
}

// Height of the occlusal surface above the volume's centre line.
double surfaceHeight(const VoxelScene& scene) {
  double y = 12e-3;
  while (y > 0.0 && !scene.inside({0.0, y, 0.0})) y -= 0.01e-3;
  return y;
}

// `feltOffset`: how far above the surface the part each algorithm feels sits
// when the burr centre is on the surface (0 for #1's centre vertex, the burr
// radius for #2's sphere points). The felt part is pressed 0.3 mm in.
void run(benchmark::State& state, const HapticsRendererNode& renderer, double feltOffset) {
  VoxelScene scene;
  scene.addVolume(phantom(), glm::dmat4(1.0), 700.0);
  const double y = surfaceHeight(scene) + feltOffset - 0.3e-3;
  auto algorithm = renderer.compile(kTool, scene);
  // Approach from above so the proxies see the contact begin.
  algorithm->reset(Pose{{0.0, 12e-3, 0.0}, glm::dquat(1, 0, 0, 0)});
  for (int i = 0; i <= 100; ++i)
    algorithm->step(scene, {Pose{{0.0, 12e-3 + (y - 12e-3) * i / 100.0, 0.0}, glm::dquat(1, 0, 0, 0)}, 1e-3});
  std::vector<double> us;
  us.reserve(1 << 16);
  long n = 0;
  int contacts = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const HapticOutput out = algorithm->step(scene, {contactPose(n++, y), 1e-3});
    const auto t1 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(out.force);
    contacts = std::max(contacts, out.contacts);
    if (us.size() < us.capacity()) us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  std::sort(us.begin(), us.end());
  if (!us.empty()) {
    state.counters["p50_us"] = us[us.size() / 2];
    state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  }
  state.counters["contacts"] = contacts;
}

void BM_LineProxy(benchmark::State& state) {
  LineProxyRenderer r;
  r.vertexCount.set(int(state.range(0)) + 1);  // the paper counts shaft vertices; +1 for the burr centre
  run(state, r, kTool.tipRadius);  // #1 feels the burr's surface (feelBurrSurface, the default)
}
BENCHMARK(BM_LineProxy)->Arg(50)->Arg(100)->Arg(250)->Arg(500)->Arg(1000)->Unit(benchmark::kMicrosecond);

// #1's tip model at the paper's 51 vertices, in one run: 0 = the paper's
// centre vertex (felt at the burr centre), 1 = the burr's surface (BurrField).
void BM_LineProxyTipModel(benchmark::State& state) {
  LineProxyRenderer r;
  const bool surface = state.range(0) != 0;
  r.feelBurrSurface.set(surface);
  run(state, r, surface ? kTool.tipRadius : 0.0);
}
BENCHMARK(BM_LineProxyTipModel)->ArgName("burrSurface")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_SurfacePoint(benchmark::State& state) {
  SurfacePointRenderer r;
  r.slices.set(int(state.range(0)));
  run(state, r, kTool.tipRadius);
}
BENCHMARK(BM_SurfacePoint)->Arg(10)->Arg(20)->Arg(30)->Arg(50)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
