#pragma once
#include <cstdint>

#include "millsim/core/NodeKinds.h"

namespace millsim {

// A clock for animations (X3D's time-dependent node). MillSim's time is the
// seconds since the run started — simulated time in `millsim replay` and
// `render`, the run's own clock in `millsim run` — so startTime 0 means "at
// the start of the run". The event clock (EventClock) evaluates every
// TimeSensor at each tick; its outputs then cascade along the routes.
class TimeSensor : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString description{this, "description", Access::InputOutput, "", "A text for people. Accepted; not acted on by MillSim."};
  SFBool enabled{this, "enabled", Access::InputOutput, true, "Whether the sensor runs; FALSE stops it (isActive FALSE)."};
  SFTime cycleInterval{this, "cycleInterval", Access::InputOutput, Time{1.0},
                       "Length of one cycle of fraction_changed from 0 to 1 (s).", Range::openClosed(0, 1e9)};
  SFBool loop{this, "loop", Access::InputOutput, false, "Whether cycles repeat until stopTime (else one cycle)."};
  SFTime startTime{this, "startTime", Access::InputOutput, Time{0.0},
                   "When it becomes active (s since the run's start).", Range::closed(-1e9, 1e9)};
  SFTime stopTime{this, "stopTime", Access::InputOutput, Time{0.0},
                  "When it stops (s since the run's start); ignored when not after startTime.", Range::closed(-1e9, 1e9)};
  SFTime pauseTime{this, "pauseTime", Access::InputOutput, Time{0.0},
                   "When it pauses (s), if after startTime; paused time does not count.", Range::closed(-1e9, 1e9)};
  SFTime resumeTime{this, "resumeTime", Access::InputOutput, Time{0.0},
                    "When a pause ends (s), if after pauseTime (else the pause lasts until stopTime).", Range::closed(-1e9, 1e9)};
  SFTime cycleTime{this, "cycleTime", Access::OutputOnly, Time{0.0}, "The time each cycle starts (s)."};
  SFFloat fraction_changed{this, "fraction_changed", Access::OutputOnly, 0.f,
                           "Where in the cycle it is, 0 to 1, sent every tick while active."};
  SFTime time{this, "time", Access::OutputOnly, Time{0.0}, "The current time (s), sent every tick while active."};
  SFBool isActive{this, "isActive", Access::OutputOnly, false, "TRUE when it starts running, FALSE when it stops."};
  SFBool isPaused{this, "isPaused", Access::OutputOnly, false, "TRUE when it pauses, FALSE when it resumes."};
  SFTime elapsedTime{this, "elapsedTime", Access::OutputOnly, Time{0.0},
                     "Seconds active since it started, pauses excluded."};

  // Sets the outputs for time `now` (s since the run's start); true if it sent an event.
  bool evaluate(double now);

private:
  bool active_ = false, paused_ = false;
  double start_ = 0.0;      // startTime when it became active
  double pausedAt_ = 0.0;   // when the current pause began
  double pausedFor_ = 0.0;  // paused seconds so far in this activation
  double handledPause_ = 0.0;  // the pauseTime already acted on (NaN: none)
  std::int64_t cycle_ = -1;  // the cycle whose cycleTime was sent
};

}  // namespace millsim
