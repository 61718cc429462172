#pragma once
// Deterministic replay, as one call over a Session (millsim/session/Session.h)
// driven in simulated time: runs a scene's device through a trajectory at a fixed
// rate in simulated time (HapticLoop::stepSimulated), milling when the button
// is on, and writes one log row per frame (FrameLog.h). A TrajectoryDevice
// plays it open loop, a HandDevice follows it closed loop, a hardware device
// is replaced by the trajectory. The same scene, trajectory and options give
// the same bytes on every run (compute time is only logged on request,
// because wall-clock time is the one thing that cannot repeat). The scene's
// events (TimeSensors and what they drive, millsim/std/EventClock.h) tick
// every 20 ms of the same simulated time, from 0 at the first frame.
#include <functional>
#include <limits>
#include <memory>
#include <ostream>
#include <string>

#include "millsim/core/Scene.h"
#include "millsim/devices/RecordedRun.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/haptics/HapticsRenderer.h"
#include "millsim/run/HapticLoop.h"

namespace millsim {

struct ReplayOptions {
  double rate = 0.0;             // Hz; 0 = the device's desiredHapticsRate
  std::string renderer;          // replace the scene's renderer with a default one of this type
  bool timing = false;           // fill frame_us with measured compute time
  double until = std::numeric_limits<double>::infinity();  // stop after this trajectory time (s)
  std::function<void(const FrameRecord&)> onFrame;         // called with every frame, in order (the milling sound)
  std::function<void(HapticLoop&)> onLoop;  // called once the loop is made, before the first frame (block channels)
};

struct ReplaySummary {
  std::string rendererName;
  double rate = 0.0;  // Hz
  // Frames, peak force (after the safety layer) and torque, contacts,
  // removed volume, suppressed non-finite outputs; compute time only with timing.
  LoopStats stats;
  HapticOutput last;  // the final frame's output (e.g. where to draw the tool)
};

// Throws std::runtime_error with a clear message if the scene has no device,
// no renderer, or an unknown --renderer type.
ReplaySummary replay(Scene& scene, const Trajectory& trajectory, std::ostream* log, const ReplayOptions& options);

// Review: steps the scene through a recorded run's frames (RecordedRun.h) —
// the device poses, button, times and periods the renderer got, whatever the
// device was — so the run's forces and milling come out again, bit for bit
// (docs/algorithms.md, "Review"). The renderer the log names first is used
// unless options.renderer says otherwise; where the log's renderer column
// changes, the same swap (with its cross-fade) happens at the same frame.
// options.rate must be the run's rate for the frame time steps to match.
ReplaySummary replayRecorded(Scene& scene, const RecordedRun& recorded, std::ostream* log, const ReplayOptions& options);

}  // namespace millsim
