#include "millsim/run/Replay.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/run/FrameLog.h"
#include "millsim/run/RendererPool.h"
#include "millsim/std/EventClock.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

namespace {

CompiledRun compileForReplay(Scene& scene, const std::string& renderer, const ReplayOptions& options) {
  CompiledRun run = compileRun(scene, renderer);
  if (options.rate != 0.0) run.settings.rate = options.rate;
  if (!(run.settings.rate > 0.0) || !std::isfinite(run.settings.rate))
    throw std::runtime_error("the haptic rate must be positive");
  run.settings.timing = options.timing;
  run.settings.logCapacity = 4;  // drained after every frame
  return run;
}

// After the last frame: the stop row, the summary, and the results reported
// back into the scene's fields (scene thread, after the run).
ReplaySummary finishReplay(HapticLoop& loop, FrameLogWriter& writer, CompiledRun& run, const std::string& rendererName,
                           const ReplayOptions& options) {
  // The summary and the device's fields describe the last haptic frame; the
  // log ends, as a live run's does, with the zero output of the stop.
  const FrameRecord lastFrame = writer.last();
  loop.finish();
  writer.drain(loop);
  const LoopStats s = loop.stats();
  ReplaySummary summary;
  summary.rendererName = rendererName;
  summary.rate = run.settings.rate;
  summary.frames = s.frames;
  summary.peakForce = s.peakForce;
  summary.peakTorque = s.peakTorque;
  summary.maxContacts = s.maxContacts;
  summary.contactFrames = s.contactFrames;
  summary.removedVolume = s.removedVolume;
  summary.suppressed = s.suppressed;
  if (options.timing) {
    summary.meanFrameUs = s.computeUs.mean();
    summary.p99FrameUs = s.computeUs.percentile(0.99);
  }
  summary.last = lastFrame.out;
  publishToDevice(*run.device, lastFrame, summary.rate);
  publishRemovedVolumes(run);
  return summary;
}

// The recorded run's device is not opened: the loop writes its output here.
class RecordedOutput final : public DeviceDriver {
public:
  DeviceReading read(double, double) override { return {}; }
  void write(const glm::dvec3&, const glm::dvec3&) override {}
};

}  // namespace

ReplaySummary replay(Scene& scene, const Trajectory& trajectory, std::ostream* log, const ReplayOptions& options) {
  CompiledRun run = compileForReplay(scene, options.renderer, options);
  std::unique_ptr<DeviceDriver> driver = run.device->followsTrajectory()
                                             ? run.device->openDriver(DriverOptions{&trajectory})
                                             : makeTrajectoryDriver(trajectory, false);
  const double t0 = trajectory.startTime();
  const double t1 = std::min(trajectory.endTime(), std::max(t0, options.until));
  // Frame times come from an integer count so that no rounding drifts.
  const long frames = long(std::floor((t1 - t0) * run.settings.rate + 1e-9)) + 1;

  const std::string rendererName = run.rendererName;
  HapticLoop loop(*run.scene, std::move(run.algorithm), std::move(driver), run.settings);
  if (options.onLoop) options.onLoop(loop);
  FrameLogWriter writer(log);
  if (options.onFrame) writer.observe(options.onFrame);
  // The scene's events (TimeSensors, interpolators) in the same simulated time, as the scene thread of a run.
  EventClock events(scene);
  for (long n = 0; n < frames; ++n) {
    loop.stepSimulated();
    writer.drain(loop);
    if (!events.empty()) {  // a route from removedVolume shows the replay's progress
      publishRemovedVolumes(run);
      events.advanceTo(double(n) / run.settings.rate);
    }
  }
  return finishReplay(loop, writer, run, rendererName, options);
}

ReplaySummary replayRecorded(Scene& scene, const RecordedRun& recorded, std::ostream* log, const ReplayOptions& options) {
  const auto& names = recorded.renderers();
  const auto& frames = recorded.frames();
  const std::string first = names.empty() ? std::string() : names[std::size_t(std::max(frames.front().renderer, 0))];
  // The review mills with the burr the run milled with, from its first frame.
  const auto& tools = recorded.tools();
  MillTool* toolNode = nullptr;
  if (HapticsDevice* device = findDevice(scene)) toolNode = device->tool.get().get();
  if (toolNode && frames.front().tool >= 0) toolNode->setGeometry(tools[std::size_t(frames.front().tool)]);
  CompiledRun run = compileForReplay(scene, options.renderer.empty() ? first : options.renderer, options);
  // The log's poses are world poses, calibration already applied.
  run.settings.calibrationRotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
  run.settings.calibrationOffset = glm::dvec3(0.0);

  // Swaps the run made (a renderer or tool column that changes) are made
  // again, at the same frames, with renderers prepared as the live run
  // prepared them (a --renderer override keeps to its renderer).
  const bool swaps = options.renderer.empty() && names.size() > 1;
  const bool burrSwaps = toolNode && tools.size() > 1;
  std::unique_ptr<RendererPool> pool;
  if (swaps || burrSwaps) pool = std::make_unique<RendererPool>(scene, run, run.algorithm.get());
  auto slotOf = [&](const std::string& type) {
    const auto types = pool->typeNames();
    const auto it = std::find(types.begin(), types.end(), type);
    if (it == types.end())
      throw std::runtime_error("the recorded run switches to renderer '" + type + "', which this scene cannot prepare");
    return std::size_t(it - types.begin());
  };

  const std::string rendererName = run.rendererName;
  HapticLoop loop(*run.scene, std::move(run.algorithm), std::make_unique<RecordedOutput>(), run.settings);
  if (options.onLoop) options.onLoop(loop);
  FrameLogWriter writer(log);
  if (options.onFrame) writer.observe(options.onFrame);
  int renderer = frames.front().renderer, tool = frames.front().tool;
  EventClock events(scene);
  for (const RecordedFrame& f : frames) {
    if (f.t > options.until) break;
    if (swaps && f.renderer != renderer) {
      pool->collect(loop);
      const std::string& next = names[std::size_t(f.renderer)];
      pool->select(slotOf(next), loop);
      renderer = f.renderer;
    }
    if (burrSwaps && f.tool != tool) {
      pool->collect(loop);
      toolNode->setGeometry(tools[std::size_t(f.tool)]);
      const std::string said = pool->followTool(loop);
      if (!(pool->tool() == tools[std::size_t(f.tool)]))
        throw std::runtime_error("the recorded run swaps to a burr this review cannot: " + said);
      tool = f.tool;
    }
    loop.stepRecorded(f.t, f.periodUs, f.device, f.button);
    writer.drain(loop);
    if (!events.empty()) {  // a route from removedVolume shows the replay's progress
      publishRemovedVolumes(run);
      events.advanceTo(f.t - frames.front().t);
    }
  }
  if (pool) pool->collect(loop);
  return finishReplay(loop, writer, run, rendererName, options);
}

}  // namespace millsim
