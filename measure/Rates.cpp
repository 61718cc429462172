#include "measure/Rates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "millsim/run/ThreadCpuTime.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim::measure {

namespace {

const ToolGeometry kTool{0.6e-3, 0.4e-3, 15e-3};  // as bench/RendererBench.cpp
constexpr double kProcedureHoleDepth = 2.5e-3;    // the §8.2 procedure's hole

double occlusalTop(const VoxelScene& scene) {
  double top = 12e-3;
  while (top > 0.0 && !scene.inside({0.0, top, 0.0})) top -= 0.01e-3;
  return top;
}

// The phantom, milled for the deep pose: a vertical hole of the burr's radius
// down from the occlusal surface at x = z = 0. Built once per grid and pose.
VoxelVolume& phantom(bool fine, RatePose pose) {
  static std::map<std::pair<bool, RatePose>, VoxelVolume> made;
  auto key = std::make_pair(fine, pose);
  auto it = made.find(key);
  if (it != made.end()) return it->second;
  VoxelVolume v = fine ? makeToothPhantom(ToothPhantomOptions{{512, 512, 352}, 0.05e-3, false})
                       : makeToothPhantom(ToothPhantomOptions{});
  VoxelVolume& volume = made.emplace(key, std::move(v)).first->second;
  if (pose == RatePose::Deep) {
    VoxelScene scene;
    scene.addVolume(volume, glm::dmat4(1.0), 700.0);
    const double top = occlusalTop(scene);
    for (double d = 0.0; d <= kProcedureHoleDepth - kTool.tipRadius; d += 0.02e-3) scene.mill({0.0, top - d, 0.0}, kTool.tipRadius);
  }
  return volume;
}

Pose contactPose(long n, double y) {
  const double a = 2.0 * std::numbers::pi * double(n % 1000) / 1000.0;
  return Pose{{0.0, y, 0.0}, glm::angleAxis(0.26, glm::dvec3(std::cos(a), 0.0, std::sin(a)))};
}

}  // namespace

RateResult measureRate(const RendererSpec& spec, long frames, const std::string& label, bool fine, RatePose pose) {
  auto node = makeRenderer(spec);
  VoxelScene scene;
  VoxelVolume& volume = phantom(fine, pose);
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  const double top = occlusalTop(scene);
  // The surface the burr presses on (the occlusal surface, or the hole's bottom), then 0.3 mm further in.
  const double rest = pose == RatePose::Deep ? top - kProcedureHoleDepth : top;
  const double y = rest + contactOffset(*node, kTool, volume.voxelSize().x) - 0.3e-3;
  auto algorithm = node->compile(kTool, scene);
  const double above = top + 2e-3;
  algorithm->reset(Pose{{0.0, above, 0.0}, {1, 0, 0, 0}});
  for (int i = 0; i <= 400; ++i)
    algorithm->step(scene, {Pose{{0.0, above + (y - above) * i / 400.0, 0.0}, {1, 0, 0, 0}}, 1e-3});
  // Lean the shaft in over 100 frames, so a proxy follows instead of jumping.
  for (int i = 0; i <= 100; ++i)
    algorithm->step(scene, {Pose{{0.0, y, 0.0}, glm::slerp(glm::dquat(1, 0, 0, 0), contactPose(0, y).orientation,
                                                           i / 100.0)},
                            1e-3});
  std::vector<double> cpu(std::size_t(std::max(frames, 1L))), wall(cpu.size());
  RateResult r;
  r.renderer = spec.type, r.resolution = label, r.frames = frames;
  r.grid = fine ? "512x512x352 @ 0.05 mm" : "256x256x176 @ 0.1 mm";
  r.pose = pose == RatePose::Deep ? "deep" : "gentle";
  r.minContacts = 1 << 30;
  for (long n = 0; n < frames; ++n) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = threadCpuMicros();
    const HapticOutput out = algorithm->step(scene, {contactPose(n, y), 1e-3});
    cpu[std::size_t(n)] = threadCpuMicros() - c0;
    wall[std::size_t(n)] = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    r.preempted += wall[std::size_t(n)] - cpu[std::size_t(n)] > 10.0;
    r.maxContacts = std::max(r.maxContacts, out.contacts);
    r.minContacts = std::min(r.minContacts, out.contacts);
  }
  double sum = 0.0;
  for (double u : cpu) sum += u;
  r.meanUs = sum / double(cpu.size());
  const FrameTimes t = FrameTimes::of(cpu);
  r.p50Us = t.p50, r.p99Us = t.p99, r.p999Us = t.p999, r.maxUs = t.max;
  r.wallP99Us = FrameTimes::of(wall).p99;
  r.control = timeConstantWork(r.p50Us, frames);
  r.rateHz = r.meanUs > 0.0 ? 1e6 / r.meanUs : 0.0;
  return r;
}

}  // namespace millsim::measure
