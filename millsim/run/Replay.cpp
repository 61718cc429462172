#include "millsim/run/Replay.h"

#include <cmath>
#include <stdexcept>

#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/run/FrameLog.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

ReplaySummary replay(Scene& scene, const Trajectory& trajectory, std::ostream* log, const ReplayOptions& options) {
  CompiledRun run = compileRun(scene, options.renderer);
  if (options.rate != 0.0) run.settings.rate = options.rate;
  if (!(run.settings.rate > 0.0) || !std::isfinite(run.settings.rate))
    throw std::runtime_error("the haptic rate must be positive");
  run.settings.timing = options.timing;
  run.settings.logCapacity = 4;  // drained after every frame
  std::unique_ptr<DeviceDriver> driver = run.device->followsTrajectory()
                                             ? run.device->openDriver(DriverOptions{&trajectory})
                                             : makeTrajectoryDriver(trajectory, false);

  ReplaySummary summary;
  summary.rendererName = run.rendererName;
  summary.rate = run.settings.rate;
  const double t0 = trajectory.startTime();
  const double t1 = std::min(trajectory.endTime(), std::max(t0, options.until));
  // Frame times come from an integer count so that no rounding drifts.
  const long frames = long(std::floor((t1 - t0) * run.settings.rate + 1e-9)) + 1;

  HapticLoop loop(*run.scene, std::move(run.algorithm), std::move(driver), run.settings);
  FrameLogWriter writer(log);
  if (options.onFrame) writer.observe(options.onFrame);
  for (long n = 0; n < frames; ++n) {
    loop.stepSimulated();
    writer.drain(loop);
  }
  loop.finish();
  const LoopStats s = loop.stats();
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
  summary.last = writer.last().out;
  // Report back into the scene's fields (scene thread, after the run).
  publishToDevice(*run.device, writer.last(), summary.rate);
  for (std::size_t i = 0; i < run.scene->volumeCount(); ++i) {
    auto& v = run.scene->volume(i);
    if (v.node) v.node->removedVolume.set(float(v.miller.totalRemoved()));
  }
  return summary;
}

}  // namespace millsim
