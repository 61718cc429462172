#include "millsim/run/RunSetup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

CompiledRun::CompiledRun() = default;
CompiledRun::~CompiledRun() = default;
CompiledRun::CompiledRun(CompiledRun&&) noexcept = default;
CompiledRun& CompiledRun::operator=(CompiledRun&&) noexcept = default;

HapticsDevice* findDevice(const Scene& scene) {
  auto devices = scene.nodesOfType<HapticsDevice>();
  return devices.empty() ? nullptr : devices.front();
}

namespace {

const HapticsRendererNode* rendererOfType(Scene& scene, const std::string& typeName,
                                          std::shared_ptr<Node>& keepAlive) {
  keepAlive = scene.registry.create(typeName);
  auto* renderer = dynamic_cast<const HapticsRendererNode*>(keepAlive.get());
  if (renderer) return renderer;
  std::string names;
  for (const NodeType* t : scene.registry.all()) {
    auto probe = t->create();
    if (dynamic_cast<HapticsRendererNode*>(probe.get())) names += (names.empty() ? "" : ", ") + t->name;
  }
  throw std::runtime_error("unknown renderer type '" + typeName + "' (expected one of: " + names + ")");
}

}  // namespace

CompiledRun compileRun(Scene& scene, const std::string& rendererOverride) {
  CompiledRun run;
  run.device = findDevice(scene);
  if (!run.device)
    throw std::runtime_error("the scene has no device node (e.g. <HandDevice> or <TrajectoryDevice>) to run");
  MillTool defaultTool;
  run.tool = run.device->tool.get() ? run.device->tool.get()->geometry() : defaultTool.geometry();
  run.scene = std::make_unique<VoxelScene>(scene);
  run.settings = LoopSettings::from(*run.device, run.tool);
  if (!rendererOverride.empty()) {
    run.algorithm = compileRenderer(scene, rendererOverride, run);
  } else {
    const HapticsRendererNode* renderer = run.device->hapticsRenderer.get().get();
    if (!renderer)
      throw std::runtime_error(run.device->typeName() +
                               " has no haptics renderer; add one to the scene or pass --renderer");
    run.algorithm = renderer->compile(run.tool, *run.scene);
  }
  run.rendererName = run.algorithm->name();
  return run;
}

std::unique_ptr<HapticAlgorithm> compileRenderer(Scene& scene, const std::string& typeName, const CompiledRun& run) {
  std::shared_ptr<Node> node;
  return rendererOfType(scene, typeName, node)->compile(run.tool, *run.scene);
}

namespace {
Rotation toRotation(glm::dquat q) {
  if (q.w < 0.0) q = -q;
  const double angle = 2.0 * std::acos(std::clamp(q.w, -1.0, 1.0));
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  return s > 1e-12 ? Rotation{glm::vec3(v / s), float(angle)} : Rotation{};
}
}  // namespace

void publishToDevice(HapticsDevice& device, const FrameRecord& r, double rate) {
  device.devicePosition.set(glm::vec3(r.device.position));
  device.deviceOrientation.set(toRotation(r.device.orientation));
  device.force.set(glm::vec3(r.force));
  device.torque.set(glm::vec3(r.torque));
  device.mainButton.set(r.button);
  device.inContact.set(r.out.contacts > 0);
  device.contactForce.set(float(glm::length(r.force)));
  device.proxyPosition.set(glm::vec3(r.out.drawnTool.position));
  device.proxyOrientation.set(toRotation(r.out.drawnTool.orientation));
  device.hapticsRate.set(float(rate));
  device.hapticsLoopTime.set(Time{r.computeUs * 1e-6});
}

void publishRemovedVolumes(const CompiledRun& run) {
  for (std::size_t i = 0; i < run.scene->volumeCount(); ++i) {
    auto& v = run.scene->volume(i);
    const float removed = float(v.miller.totalRemoved());
    if (v.node && removed != v.node->removedVolume.get()) v.node->removedVolume.set(removed);
  }
}

}  // namespace millsim
