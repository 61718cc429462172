#include "RunSummary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>

#include "Commands.h"
#include "SaveMesh.h"
#include "SaveVolume.h"
#include "millsim/std/WorldInfo.h"

namespace millsim::app {

std::string windowTitle(const Scene& scene, const std::string& file) {
  for (const WorldInfo* info : scene.nodesOfType<WorldInfo>())
    if (!info->title.get().empty()) return "MillSim — " + info->title.get();
  return "MillSim — " + std::filesystem::path(file).filename().string();
}

void printRunSummary(std::ostream& os, const SessionResult& r) {
  const LoopStats& s = r.stats;
  os << std::fixed;
  os << "ran " << s.frames << " frames in " << std::setprecision(2) << s.elapsed << " s with " << r.renderer << " on "
     << r.device << " (desired " << std::setprecision(0) << r.rate << " Hz)\n";
  os << "  haptic rate: mean " << std::setprecision(1) << s.meanRate() << " Hz, p1 " << s.p1Rate()
     << " Hz, missed deadlines " << s.missedDeadlines << " of " << s.frames << " ("
     << std::setprecision(2) << (s.frames ? 100.0 * double(s.missedDeadlines) / double(s.frames) : 0.0)
     << " %); over their period on the thread's CPU " << s.overrunFrames << " ("
     << (s.frames ? 100.0 * double(s.overrunFrames) / double(s.frames) : 0.0) << " %)\n";
  os << "  compute per frame: mean " << std::setprecision(1) << s.computeUs.mean() << " µs, p99 "
     << s.computeUs.percentile(0.99) << " µs, max " << s.computeUs.max() << " µs (wall); on the thread's CPU p99 "
     << s.computeCpuUs.percentile(0.99) << " µs, max " << s.computeCpuUs.max() << " µs; " << s.preemptedFrames
     << " frames lost the CPU for over " << std::setprecision(0) << LoopStats::kPreemptedUs << " µs\n";
  os << "  peak force " << std::setprecision(3) << s.peakForce << " N, peak torque " << std::setprecision(4)
     << s.peakTorque << " N·m, frames in contact " << s.contactFrames << ", most contacts " << s.maxContacts << "\n";
  if (!s.outputsTorque)
    os << "  torque: rendered, not output (the device applies force only): " << s.torqueNotOutput
       << " frames of torque logged and flagged " << kSafetyTorqueNotOutput << "\n";
  if (s.firstForceAt >= 0.0)
    os << "  first force over 1 mN sent " << std::setprecision(3) << s.firstForceAt << " s into the run\n";
  os << "  removed volume " << std::setprecision(3) << s.removedVolume * 1e9 << " mm³\n";
  os << "  safety: clamped " << s.safety.clamped << ", late frames blended " << s.safety.hiccups << ", watchdog trips "
     << s.safety.watchdogTrips << ", non-finite "
     << s.safety.nonFinite << "; device: sequence gaps " << s.device.sequenceGaps << ", checksum errors "
     << s.device.checksumErrors << "; log records dropped " << s.recordsDropped << "\n";
  os << "  real-time priority: "
     << (s.deviceServo        ? "the device library's own servo thread"
         : s.realTimePriority ? "SCHED_FIFO"
                            : "not granted (normal priority); to grant it, raise the rtprio limit (ulimit -r 99, or "
                              "'@audio - rtprio 99' in /etc/security/limits.conf) or give the binary CAP_SYS_NICE "
                              "(setcap cap_sys_nice+ep millsim)")
     << "\n";
  os.unsetf(std::ios::fixed);
}

void printReplaySummary(std::ostream& os, const SessionResult& r, bool timing) {
  const LoopStats& s = r.stats;
  os << "replayed " << s.frames << " frames at " << r.rate << " Hz with " << r.renderer << "\n"
     << "  peak force " << s.peakForce << " N, peak torque " << s.peakTorque << " N·m, frames in contact "
     << s.contactFrames << ", most contacts " << s.maxContacts << "\n"
     << "  removed volume " << s.removedVolume * 1e9 << " mm³, suppressed non-finite outputs " << s.suppressed << "\n";
  if (timing)
    os << "  compute time per frame: mean " << s.computeUs.mean() << " µs, p99 " << s.computeUs.percentile(0.99)
       << " µs\n";
}

int finishOutputs(std::ostream& out, std::ostream& err, const SessionResult& s, const Scene& scene,
                  const RunOutputs& o, bool logOk) {
  const std::string prefix = "millsim " + o.verb + ": error: ";
  if (!logOk) {
    err << prefix << o.log << ": writing the log failed\n";
    return kExitFailure;
  }
  out << s.soundSummary;
  try {
    if (!o.report.empty()) {
      const LessonReport report = s.report(o.sceneFile);
      writeReport(o.report, report);
      out << describeReport(report, false) << "  report written to " << o.report << "\n";
    }
    if (!o.saveVolume.empty()) out << saveVolume(scene, o.saveVolume);
    if (!o.saveMesh.empty()) out << saveMesh(scene, o.saveMesh);
  } catch (const std::exception& e) {
    err << prefix << e.what() << "\n";
    return kExitFailure;
  }
  if (const auto& g = s.graphics) {
    out << std::fixed << std::setprecision(1) << (g->window ? "  window: " : "  graphics: ") << g->frames
        << " frames at " << g->width << "x" << g->height << ", mean " << g->meanMs << " ms, p95 " << g->p95Ms
        << " ms, with re-meshing " << g->meanUpdateMs << " ms (" << g->updateFrames << " frames); first mesh "
        << g->meshSeconds * 1e3 << " ms; first frame " << g->firstFrameSeconds * 1e3 << " ms after start; " << g->gl
        << "\n";
    out.unsetf(std::ios::fixed);
    if (!g->screenshot.empty() && s.graphicsError.empty()) out << "  screenshot: " << g->screenshot << "\n";
  }
  if (!s.graphicsError.empty()) err << prefix << s.graphicsError << "\n";
  if (!s.soundError.empty()) err << prefix << s.soundError << "\n";
  if (!s.failure.empty())
    // The loop has already zeroed the output and released the device.
    err << prefix << s.failure << (o.log.empty() ? "" : " (the log up to that frame is in " + o.log + ")") << "\n";
  // A renderer that produced NaN or Inf on a device: nothing of it was sent,
  // but the run is not one to trust (the hand felt zero meanwhile).
  const long nonFinite = std::max<long>(long(s.stats.safety.nonFinite), s.stats.suppressed);
  if (o.verb == "run" && nonFinite > 0) {
    err << prefix << s.renderer << " produced non-finite output in " << nonFinite
        << " frames; none was sent (the device got zero, then a soft start)\n";
    return kExitFailure;
  }
  return s.ok() ? kExitOk : kExitFailure;
}

}  // namespace millsim::app
