#include "millsim/std/TimeSensor.h"

#include <cmath>
#include <limits>

namespace millsim {

const NodeType& TimeSensor::type() {
  static const NodeType t = makeNodeType<TimeSensor>(
      "TimeSensor", "children", "Time",
      "A clock: while active it sends time, fraction_changed and elapsedTime at every tick of the scene thread's "
      "event clock (about 50 Hz in `millsim run`). Times are seconds since the run's start.");
  return t;
}

bool TimeSensor::evaluate(double now) {
  if (!enabled.get()) {
    if (!active_) return false;
    active_ = paused_ = false;
    isActive.set(false);
    return true;
  }
  const double start = startTime.get().seconds, stop = stopTime.get().seconds;
  const double interval = cycleInterval.get().seconds;
  const bool hasStop = stop > start;  // X3D: a stopTime at or before startTime is ignored
  bool sent = false;
  if (!active_) {
    // Not yet started, stopped, or one cycle that is already over: stays inactive.
    if (now < start || (hasStop && now >= stop) || (!loop.get() && now >= start + interval)) return false;
    active_ = true;
    paused_ = false;
    start_ = start;
    pausedFor_ = 0.0;
    handledPause_ = std::numeric_limits<double>::quiet_NaN();
    cycle_ = -1;
    isActive.set(true);
    sent = true;
  }
  // A pause from pauseTime until resumeTime (if that is later); each pauseTime once.
  const double pause = pauseTime.get().seconds, resume = resumeTime.get().seconds;
  if (!paused_ && pause > start_ && now >= pause && pause != handledPause_) {
    handledPause_ = pause;
    if (resume > pause && now >= resume) {
      pausedFor_ += resume - pause;  // the whole pause fell between two ticks
    } else {
      paused_ = true;
      pausedAt_ = pause;
      isPaused.set(true);
      return true;
    }
  }
  if (paused_) {
    if (!(resume > pausedAt_ && now >= resume)) {
      if (!(hasStop && now >= stop)) return sent;
      active_ = paused_ = false;  // stopped while paused
      isPaused.set(false);
      isActive.set(false);
      return true;
    }
    paused_ = false;
    pausedFor_ += resume - pausedAt_;
    isPaused.set(false);
    sent = true;
  }
  // The stop time ends the run at stopTime itself, with that time's fraction.
  const bool stopping = hasStop && now >= stop;
  const double at = stopping ? stop : now;
  const double elapsed = std::max(0.0, at - start_ - pausedFor_);
  const bool lastCycle = !loop.get() && elapsed >= interval;
  double fraction;
  if (lastCycle) {
    fraction = 1.0;
  } else {
    const double cycles = std::floor(elapsed / interval);
    fraction = elapsed / interval - cycles;
    if (fraction == 0.0 && elapsed > 0.0) fraction = 1.0;  // X3D: the end of a cycle is 1, not 0
    if (std::int64_t(cycles) > cycle_) {
      cycle_ = std::int64_t(cycles);
      cycleTime.set(Time{at});
    }
  }
  time.set(Time{at});
  elapsedTime.set(Time{elapsed});
  fraction_changed.set(float(fraction));
  if (lastCycle || stopping) {
    active_ = false;
    isActive.set(false);
  }
  return true;
}

}  // namespace millsim
