#include "measure/Rates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim::measure {

namespace {

VoxelVolume& phantom(bool fine) {
  if (fine) {
    static VoxelVolume v = makeToothPhantom(ToothPhantomOptions{{512, 512, 352}, 0.05e-3, false});
    return v;
  }
  static VoxelVolume v = makeToothPhantom(ToothPhantomOptions{});
  return v;
}

const ToolGeometry kTool{0.6e-3, 0.4e-3, 15e-3};  // as bench/RendererBench.cpp

Pose contactPose(long n, double y) {
  const double a = 2.0 * std::numbers::pi * double(n % 1000) / 1000.0;
  return Pose{{0.0, y, 0.0}, glm::angleAxis(0.26, glm::dvec3(std::cos(a), 0.0, std::sin(a)))};
}

}  // namespace

RateResult measureRate(const RendererSpec& spec, long frames, const std::string& label, bool fine) {
  auto node = makeRenderer(spec);
  VoxelScene scene;
  VoxelVolume& volume = phantom(fine);
  scene.addVolume(volume, glm::dmat4(1.0), 700.0);
  double top = 12e-3;
  while (top > 0.0 && !scene.inside({0.0, top, 0.0})) top -= 0.01e-3;
  const double y = top + contactOffset(*node, kTool, volume.voxelSize().x) - 0.3e-3;
  auto algorithm = node->compile(kTool, scene);
  algorithm->reset(Pose{{0.0, 12e-3, 0.0}, {1, 0, 0, 0}});
  for (int i = 0; i <= 100; ++i)
    algorithm->step(scene, {Pose{{0.0, 12e-3 + (y - 12e-3) * i / 100.0, 0.0}, {1, 0, 0, 0}}, 1e-3});
  std::vector<double> us(std::size_t(std::max(frames, 1L)));
  RateResult r{spec.type, label, fine ? "512x512x352 @ 0.05 mm" : "256x256x176 @ 0.1 mm", frames};
  for (long n = 0; n < frames; ++n) {
    const auto t0 = std::chrono::steady_clock::now();
    const HapticOutput out = algorithm->step(scene, {contactPose(n, y), 1e-3});
    us[std::size_t(n)] = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    r.maxContacts = std::max(r.maxContacts, out.contacts);
  }
  double sum = 0.0;
  for (double u : us) sum += u;
  r.meanUs = sum / double(us.size());
  std::sort(us.begin(), us.end());
  r.p50Us = us[us.size() / 2];
  r.p99Us = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  r.rateHz = r.meanUs > 0.0 ? 1e6 / r.meanUs : 0.0;
  return r;
}

}  // namespace millsim::measure
