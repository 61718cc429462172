#pragma once
// EventClock: what drives time in a scene, on the scene thread. Each tick at
// time t (seconds since the run's start) evaluates every enabled TimeSensor,
// delivers the keys that arrived since the last tick to the KeySensors, and
// runs the event cascade: every EventNode (interpolators, filters, triggers)
// with a new input event turns it into output events, until none has one.
// Ordinary fields downstream (a Transform's translation) pull their new value
// when next read, as every field does (millsim/core/Field.h).
//
// X3D's rules: all events of one cascade share its timestamp; each node sends
// at most once per timestamp, so a cycle of routes ends, and an event that
// comes back round a cycle to a node that already sent is dropped. Each key is
// its own timestamp, after the time sensors' one.
#include <cstddef>
#include <limits>
#include <vector>

#include "millsim/std/KeySensor.h"

namespace millsim {

class EventNode;
class Scene;
class TimeSensor;

// The scene thread's tick: `millsim run` ticks every 20 ms of the run's
// clock; replay and render tick at the same period of simulated time.
inline constexpr double kEventTickSeconds = 0.02;

class EventClock {
public:
  // Finds the scene's sensors and event nodes (Inline contents included); the scene outlives the clock.
  explicit EventClock(const Scene& scene);

  // True when the scene has nothing that sends events (ticking does nothing).
  bool empty() const { return timeSensors_.empty() && keySensors_.empty() && eventNodes_.empty(); }
  bool hasKeySensors() const { return !keySensors_.empty(); }

  // Queues a key for the next tick.
  void key(KeyEvent e) { keys_.push_back(std::move(e)); }
  // One tick at `seconds`; returns how many nodes sent events (0: nothing changed).
  std::size_t tick(double seconds);
  // Simulated time: ticks at every multiple of kEventTickSeconds after the
  // last tick up to `seconds`, then at `seconds` itself. Deterministic.
  std::size_t advanceTo(double seconds);
  double lastTick() const { return lastTick_; }

private:
  std::size_t cascade();

  std::vector<TimeSensor*> timeSensors_;
  std::vector<KeySensor*> keySensors_;
  std::vector<EventNode*> eventNodes_;
  std::vector<KeyEvent> keys_;
  std::vector<char> sent_;  // per event node: already sent at this timestamp
  double lastTick_ = -std::numeric_limits<double>::infinity();
};

}  // namespace millsim
