#pragma once
// EventNode: the base of nodes that turn input events into output events at
// the event clock's ticks (interpolators, filters, triggers). Fields pull
// lazily (millsim/core/Field.h), which suits values but not events: a
// BooleanFilter must send inputTrue only when TRUE arrives, not whenever a
// reader looks. So the EventClock asks each EventNode, while the cascade of
// one timestamp runs, whether an input got a new event, and the node sets
// its outputs (set() stamps an event and marks the routes out stale).
#include <cstdint>

#include "millsim/core/NodeKinds.h"

namespace millsim {

class EventNode : public ChildNode {
public:
  // Called by EventClock during one timestamp's cascade, at most once per
  // timestamp per node (X3D's loop breaking). True if it sent an event.
  virtual bool processEvents() = 0;
  // Whether an input has an event processEvents() has not seen yet.
  virtual bool hasPendingEvent() const = 0;
  // Marks the pending input event seen without acting on it (an event that came back round a route cycle).
  virtual void dropPending() = 0;

protected:
  // True if `input` (read, so its routes deliver) changed since `seen`, which it then advances.
  template <class F> static bool takeEvent(const F& input, std::uint64_t& seen) {
    (void)input.get();
    if (input.lastEvent() <= seen) return false;
    seen = input.lastEvent();
    return true;
  }
  template <class F> static bool pending(const F& input, std::uint64_t seen) {
    (void)input.get();
    return input.lastEvent() > seen;
  }
};

}  // namespace millsim
