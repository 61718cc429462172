#include "millsim/haptics/Replay.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "millsim/haptics/HapticScene.h"
#include "millsim/haptics/HapticsDevice.h"
#include "millsim/haptics/Wrench.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

const char* replayLogHeader() {
  return "t,x,y,z,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,frame_us,"
         "draw_x,draw_y,draw_z,draw_qw,draw_qx,draw_qy,draw_qz,proxy_x,proxy_y,proxy_z,ip_x,ip_y,ip_z,"
         "button,removed_mm3,flags\n";
}

void appendLogRow(std::string& out, double t, const Pose& device, const glm::dvec3& force, const glm::dvec3& torque,
                  const HapticOutput& o, double frameUs, bool button, double removedVolume) {
  auto num = [&out](double v) {
    out += formatNumber(v);
    out += ',';
  };
  num(t);
  for (double v : {device.position.x, device.position.y, device.position.z}) num(v);
  for (double v : {device.orientation.w, device.orientation.x, device.orientation.y, device.orientation.z}) num(v);
  for (double v : {force.x, force.y, force.z, torque.x, torque.y, torque.z}) num(v);
  out += std::to_string(o.contacts) + ',';
  num(frameUs);
  const Pose& d = o.drawnTool;
  for (double v : {d.position.x, d.position.y, d.position.z, d.orientation.w, d.orientation.x, d.orientation.y,
                   d.orientation.z})
    num(v);
  for (double v : {o.proxy.x, o.proxy.y, o.proxy.z, o.intersection.x, o.intersection.y, o.intersection.z}) num(v);
  out += button ? "1," : "0,";
  num(removedVolume * 1e9);
  out += std::to_string(o.flags) + '\n';
}

HapticsDevice* findDevice(const Scene& scene) {
  auto devices = scene.nodesOfType<HapticsDevice>();
  return devices.empty() ? nullptr : devices.front();
}

ReplaySummary replay(Scene& scene, const Trajectory& trajectory, std::ostream* log, const ReplayOptions& options) {
  HapticsDevice* device = findDevice(scene);
  if (!device) throw std::runtime_error("the scene has no device node (e.g. <TrajectoryDevice>) to replay");
  MillTool defaultTool;
  const MillTool& tool = device->tool.get() ? *device->tool.get() : defaultTool;

  std::shared_ptr<Node> override;
  const HapticsRendererNode* renderer = device->hapticsRenderer.get().get();
  if (!options.renderer.empty()) {
    override = scene.registry.create(options.renderer);
    renderer = dynamic_cast<const HapticsRendererNode*>(override.get());
    if (!renderer) {
      std::string names;
      for (const NodeType* t : scene.registry.all()) {
        auto probe = t->create();
        if (dynamic_cast<HapticsRendererNode*>(probe.get())) names += (names.empty() ? "" : ", ") + t->name;
      }
      throw std::runtime_error("unknown renderer type '" + options.renderer + "' (expected one of: " + names + ")");
    }
  }
  if (!renderer)
    throw std::runtime_error(device->typeName() + " has no haptics renderer; add one to the scene or pass --renderer");

  const double rate = options.rate > 0.0 ? options.rate : double(device->desiredHapticsRate.get());
  if (!(rate > 0.0) || !std::isfinite(rate)) throw std::runtime_error("the haptic rate must be positive");
  const double dt = 1.0 / rate;
  HapticScene hs(scene);
  std::unique_ptr<HapticAlgorithm> algorithm = renderer->compile(tool.geometry(), hs);

  ReplaySummary summary;
  summary.rendererName = algorithm->name();
  summary.rate = rate;
  const double t0 = trajectory.startTime();
  // Frame times come from an integer count so that no rounding drifts.
  const double t1 = std::min(trajectory.endTime(), std::max(t0, options.until));
  const long frames = long(std::floor((t1 - t0) * rate + 1e-9)) + 1;
  std::vector<double> frameUs;
  if (options.timing) frameUs.reserve(std::size_t(frames));
  std::string row;
  if (log) *log << replayLogHeader();
  algorithm->reset(device->calibrate(trajectory.at(t0).pose));
  const double forceLimit = device->forceLimit.get(), torqueLimit = device->torqueLimit.get();
  const double tipRadius = tool.geometry().tipRadius;
  for (long n = 0; n < frames; ++n) {
    const double t = t0 + double(n) * dt;
    const TrajectorySample sample = trajectory.at(t);
    const Pose pose = device->calibrate(sample.pose);
    const auto start = std::chrono::steady_clock::now();
    HapticOutput out = algorithm->step(hs, HapticInput{pose, dt});
    // The burr cuts where the renderer says: at the device for direct
    // rendering, at the offset proxy for #1 (docs/algorithms.md).
    if (sample.button && out.burrCuts) summary.removedVolume += hs.mill(out.burrCentre, tipRadius);
    const double us =
        options.timing ? std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count()
                       : 0.0;
    if (options.timing) frameUs.push_back(us);
    const bool enabled = device->enabled.get();
    const glm::dvec3 force = enabled ? clampMagnitude(out.force, forceLimit) : glm::dvec3(0.0);
    const glm::dvec3 torque = enabled ? clampMagnitude(out.torque, torqueLimit) : glm::dvec3(0.0);
    summary.peakForce = std::max(summary.peakForce, glm::length(force));
    summary.peakTorque = std::max(summary.peakTorque, glm::length(torque));
    summary.maxContacts = std::max(summary.maxContacts, out.contacts);
    summary.contactFrames += out.contacts > 0;
    summary.suppressed += (out.flags & kFlagNonFiniteSuppressed) != 0;
    if (n + 1 == frames) summary.last = out;
    if (log) {
      row.clear();
      appendLogRow(row, t, pose, force, torque, out, us, sample.button, summary.removedVolume);
      *log << row;
    }
  }
  summary.frames = frames;
  if (!frameUs.empty()) {
    double sum = 0.0;
    for (double u : frameUs) sum += u;
    summary.meanFrameUs = sum / double(frameUs.size());
    std::sort(frameUs.begin(), frameUs.end());
    summary.p99FrameUs = frameUs[std::min(frameUs.size() - 1, std::size_t(double(frameUs.size()) * 0.99))];
  }
  // Report milling back into the scene's fields (scene thread, after the run).
  for (std::size_t i = 0; i < hs.volumeCount(); ++i) {
    auto& v = hs.volume(i);
    if (v.node) v.node->removedVolume.set(float(v.miller.totalRemoved()));
  }
  return summary;
}

}  // namespace millsim
