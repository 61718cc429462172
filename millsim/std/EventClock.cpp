#include "millsim/std/EventClock.h"

#include <algorithm>
#include <cmath>

#include "millsim/core/Scene.h"
#include "millsim/std/EventNode.h"
#include "millsim/std/TimeSensor.h"

namespace millsim {

EventClock::EventClock(const Scene& scene)
    : timeSensors_(scene.nodesOfType<TimeSensor>()),
      keySensors_(scene.nodesOfType<KeySensor>()),
      eventNodes_(scene.nodesOfType<EventNode>()) {}

std::size_t EventClock::cascade() {
  std::size_t sent = 0;
  sent_.assign(eventNodes_.size(), 0);
  for (bool progress = true; progress;) {
    progress = false;
    for (std::size_t i = 0; i < eventNodes_.size(); ++i) {
      if (sent_[i] || !eventNodes_[i]->hasPendingEvent()) continue;
      sent_[i] = 1;  // once per timestamp, whether or not it sends
      progress = true;
      if (eventNodes_[i]->processEvents()) ++sent;
    }
  }
  // What came back round a cycle to a node that already sent is dropped, not kept for the next tick.
  for (EventNode* n : eventNodes_) n->dropPending();
  return sent;
}

std::size_t EventClock::advanceTo(double seconds) {
  if (seconds <= lastTick_) return 0;
  std::size_t sent = 0;
  // Tick times from an integer count, so that no rounding drifts.
  long k = std::isfinite(lastTick_) ? long(std::floor(lastTick_ / kEventTickSeconds + 1e-9)) + 1 : 0;
  for (double t; (t = double(k) * kEventTickSeconds) < seconds - 1e-12; ++k)
    if (t > lastTick_) sent += tick(t);
  return sent + tick(seconds);
}

std::size_t EventClock::tick(double seconds) {
  lastTick_ = seconds;
  std::size_t sent = 0;
  for (TimeSensor* t : timeSensors_)
    if (t->evaluate(seconds)) ++sent;
  sent += cascade();
  for (const KeyEvent& k : keys_) {
    std::size_t keySent = 0;
    for (KeySensor* s : keySensors_)
      if (s->keyEvent(k)) ++keySent;
    if (keySent) sent += keySent + cascade();
  }
  keys_.clear();
  return sent;
}

}  // namespace millsim
