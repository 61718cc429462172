#include "measure/Procedure.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/session/Replay.h"
#include "millsim/run/RunSetup.h"
#include "millsim/run/ThreadCpuTime.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::measure {

namespace {

constexpr double kLeanDeg = 5.0;
const char* const kPhases[] = {"free", "contact", "lean", "milling", "all"};

double tiltDeg(const glm::dquat& q) {
  const glm::dvec3 axis = q * glm::dvec3(0.0, 1.0, 0.0);
  return std::acos(std::clamp(axis.y, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

std::size_t phaseOf(const FrameRecord& r) {
  if (r.out.contacts == 0) return 0;
  if (r.button) return 3;
  return tiltDeg(r.device.orientation) >= kLeanDeg ? 2 : 1;
}

}  // namespace

ProcedureResult measureProcedure(const RendererSpec& spec, const std::string& label, const std::string& scenePath,
                                 const std::string& trajectoryPath, long bruteEvery,
                                 const std::vector<LoadOptions::FieldOverride>& overrides) {
  LoadOptions load;
  load.overrides = overrides;
  LoadResult loaded = loadSceneFile(scenePath, builtinRegistry(), load);
  if (!loaded.ok()) throw std::runtime_error(loaded.report());
  Scene& scene = *loaded.scene;
  HapticsDevice* device = findDevice(scene);
  if (!device) throw std::runtime_error(scenePath + ": no device node to run");
  const std::shared_ptr<HapticsRendererNode> renderer = makeRenderer(spec);
  device->hapticsRenderer.set(renderer);
  const Trajectory trajectory = Trajectory::load(trajectoryPath);

  std::vector<std::vector<double>> times(std::size(kPhases));
  std::vector<double> brute;
  ProcedureResult result;
  result.renderer = spec.type;
  result.resolution = label;
  HapticLoop* loop = nullptr;
  long millingFrames = 0;
  bool afterBrute = false;  // a fresh compile cools the caches: leave the next frame out
  ReplayOptions options;
  options.timing = true;
  options.onLoop = [&](HapticLoop& l) { loop = &l; };
  options.onFrame = [&](const FrameRecord& r) {
    if (r.computeUs == 0.0 && r.cpuUs == 0.0) return;  // the stop row
    const std::size_t phase = phaseOf(r);
    if (!afterBrute) {
      times[phase].push_back(r.cpuUs);
      times.back().push_back(r.cpuUs);
    }
    afterBrute = false;
    result.preempted += r.computeUs - r.cpuUs > LoopStats::kPreemptedUs;
    result.maxContacts = std::max(result.maxContacts, r.out.contacts);
    if (phase == 3 && bruteEvery > 0 && millingFrames++ % bruteEvery == 0 && loop) {
      // Against a scene of its own over the same milled volumes: the loop's
      // scene keeps the point shells it built, and compiling against it would
      // reuse them instead of building them again.
      const double c0 = threadCpuMicros();
      VoxelScene fresh;
      for (std::size_t i = 0; i < loop->scene().volumeCount(); ++i) {
        const VoxelScene::Volume& v = loop->scene().volume(i);
        fresh.addVolume(*v.voxels, v.placement.localToWorld, v.placement.iso, nullptr, v.tissues);
      }
      auto algorithm = renderer->compile(loop->settings().tool, fresh);
      brute.push_back(threadCpuMicros() - c0);
      afterBrute = true;
    }
  };
  const ReplaySummary summary = replay(scene, trajectory, nullptr, options);
  result.removedMm3 = summary.stats.removedVolume * 1e9;
  for (std::size_t i = 0; i < std::size(kPhases); ++i) {
    ProcedurePhase p{kPhases[i], long(times[i].size()), FrameTimes::of(times[i]), {}};
    if (p.frames > 0) p.control = timeConstantWork(p.cpu.p50, std::min(p.frames, 20000L));
    result.phases.push_back(p);
  }
  result.bruteSamples = long(brute.size());
  result.brute = FrameTimes::of(brute);
  return result;
}

}  // namespace millsim::measure
